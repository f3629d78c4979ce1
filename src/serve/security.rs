//! What a server knows of its clients: the flags (`--credentials`, `--no-tls`,
//! `--access`, `--audit`), checked against the address at start, and a TLS client's
//! handshake and certificate name at each connection.

use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::Arc;

use tokio_rustls::TlsAcceptor;

use super::access::Access;
use super::audit::Audit;
use super::tls::{self, CredentialFiles};
use super::{Server, admit, conn, protocol};

/// How a server on the network knows its clients (`serve` and `fleet --listen`).
#[derive(clap::Args, Default)]
pub struct SecurityArgs {
    /// Serve TLS and authenticate clients with the credentials in DIR (server.pem,
    /// server.key, ca.pem, access.toml), as `--init-credentials DIR` makes them.
    #[arg(long, value_name = "DIR")]
    pub credentials: Option<PathBuf>,
    /// Serve plain TCP without TLS: on a loopback address only, and only when asked
    /// for with this flag.
    #[arg(long, conflicts_with = "credentials")]
    pub no_tls: bool,
    /// The clients, their roles and tokens (TOML, owner-only; docs/serve.md).
    /// Default with --credentials: DIR/access.toml. With --no-tls and no access file,
    /// every client drives and none is asked who it is.
    #[arg(long, value_name = "FILE")]
    pub access: Option<PathBuf>,
    /// Append what clients do (authentication, leases, lines, cont, stop) to FILE as
    /// JSON lines. Default with --credentials: DIR/audit.jsonl.
    #[arg(long, value_name = "FILE")]
    pub audit: Option<PathBuf>,
}

/// What a server knows of its clients, made once at start from `SecurityArgs`.
pub struct Security {
    pub tls: Option<TlsAcceptor>,
    pub access: Option<Access>,
    pub audit: Option<Audit>,
}

impl Security {
    /// Checks the flags against the address and reads the credentials.
    pub fn from_args(args: &SecurityArgs, addr: &SocketAddr) -> Result<Security, String> {
        let files = args.credentials.as_deref().map(CredentialFiles::in_dir);
        if files.is_none() && !args.no_tls {
            return Err(format!(
                "--listen {addr}: give --credentials DIR to serve TLS to authenticated \
                 clients (`ilmrc serve --init-credentials DIR` makes them), or, on a loopback \
                 address only, --no-tls"
            ));
        }
        if files.is_none() && !addr.ip().is_loopback() {
            return Err(format!(
                "--listen {addr}: plain TCP (--no-tls) is served on loopback addresses only \
                 (127.0.0.1, [::1]); beyond this machine give --credentials DIR"
            ));
        }
        let access_path = args
            .access
            .clone()
            .or_else(|| files.as_ref().map(|f| f.access.clone()));
        let access = access_path.as_deref().map(Access::load).transpose()?;
        let tls = match &files {
            Some(f) => {
                let access = access.as_ref().ok_or("TLS needs an access file")?;
                Some(tls::acceptor(f, access.wants_certificates())?)
            }
            None => None,
        };
        let audit_path = args
            .audit
            .clone()
            .or_else(|| args.credentials.as_ref().map(|dir| dir.join("audit.jsonl")));
        let audit = audit_path.as_deref().map(Audit::open).transpose()?;
        Ok(Security { tls, access, audit })
    }

    /// How the address line describes it.
    pub fn describe(&self) -> String {
        let tls = if self.tls.is_some() {
            "TLS"
        } else {
            "plain TCP"
        };
        match &self.access {
            Some(a) => format!("{tls}, {} clients known", a.len()),
            None => format!("{tls}, no authentication"),
        }
    }
}

/// A TLS client: the handshake within the request timeout (else it is closed with no
/// word, as it cannot read one), then its certificate's name, if it gave one.
pub async fn handshake(
    stream: tokio::net::TcpStream,
    peer: SocketAddr,
    place: Arc<admit::Place>,
    server: Arc<Server>,
    tls: &TlsAcceptor,
) {
    let within = server.timeouts.request;
    let Ok(Ok(mut session)) = tokio::time::timeout(within, tls.accept(stream)).await else {
        return;
    };
    let certificate = session
        .get_ref()
        .1
        .peer_certificates()
        .and_then(|c| c.first());
    if let (Some(cert), Some(access)) = (certificate, &server.access) {
        let name = tls::common_name(cert);
        match name.as_deref().and_then(|n| access.by_certificate(n)) {
            Some(identity) => {
                let _ = place.identify(identity);
            }
            None => {
                use tokio::io::AsyncWriteExt;
                let why = format!(
                    "the certificate of `{}` is not a client of this server (access file)",
                    name.as_deref().unwrap_or("?")
                );
                let line = protocol::answer(protocol::error(&why), None);
                let _ = tokio::time::timeout(within, async {
                    let _ = session.write_all(format!("{line}\n").as_bytes()).await;
                    let _ = session.shutdown().await;
                })
                .await;
                return;
            }
        }
    }
    conn::serve(session, place, server, Some(peer)).await;
}
