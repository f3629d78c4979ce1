//! TLS for `serve` (rustls, with ring's cryptography): the server's certificate and
//! key from a credentials directory, and, when the access file lets any client in by
//! certificate, client certificates checked against the directory's CA (mutual TLS).
//! A client may still come without a certificate and authenticate by token.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use rustls::pki_types::pem::PemObject;
use rustls::pki_types::{CertificateDer, PrivateKeyDer};
use tokio_rustls::TlsAcceptor;

/// The files of a credentials directory, as `--init-credentials` writes them.
pub struct CredentialFiles {
    pub ca: PathBuf,
    pub ca_key: PathBuf,
    pub server_cert: PathBuf,
    pub server_key: PathBuf,
    pub access: PathBuf,
}

impl CredentialFiles {
    pub fn in_dir(dir: &Path) -> CredentialFiles {
        CredentialFiles {
            ca: dir.join("ca.pem"),
            ca_key: dir.join("ca.key"),
            server_cert: dir.join("server.pem"),
            server_key: dir.join("server.key"),
            access: dir.join("access.toml"),
        }
    }
}

/// The server's side of TLS, made once at start.
pub fn acceptor(files: &CredentialFiles, client_certificates: bool) -> Result<TlsAcceptor, String> {
    let provider = Arc::new(rustls::crypto::ring::default_provider());
    let chain = certificates(&files.server_cert)?;
    crate::serve::access::owner_only(&files.server_key)?;
    let key = PrivateKeyDer::from_pem_file(&files.server_key).map_err(|e| {
        format!(
            "cannot read the server's key {}: {e}",
            files.server_key.display()
        )
    })?;
    let builder = rustls::ServerConfig::builder_with_provider(Arc::clone(&provider))
        .with_safe_default_protocol_versions()
        .map_err(|e| format!("TLS: {e}"))?;
    let builder = if client_certificates {
        let mut roots = rustls::RootCertStore::empty();
        for ca in certificates(&files.ca)? {
            roots
                .add(ca)
                .map_err(|e| format!("{}: not a CA certificate: {e}", files.ca.display()))?;
        }
        let verifier =
            rustls::server::WebPkiClientVerifier::builder_with_provider(Arc::new(roots), provider)
                // A client without a certificate authenticates by token instead.
                .allow_unauthenticated()
                .build()
                .map_err(|e| format!("TLS client certificates: {e}"))?;
        builder.with_client_cert_verifier(verifier)
    } else {
        builder.with_no_client_auth()
    };
    let config = builder.with_single_cert(chain, key).map_err(|e| {
        format!(
            "{} and {} do not make a server certificate: {e}",
            files.server_cert.display(),
            files.server_key.display()
        )
    })?;
    Ok(TlsAcceptor::from(Arc::new(config)))
}

fn certificates(path: &Path) -> Result<Vec<CertificateDer<'static>>, String> {
    let shown = path.display();
    let certs: Vec<_> = CertificateDer::pem_file_iter(path)
        .map_err(|e| format!("cannot read {shown}: {e}"))?
        .collect::<Result<_, _>>()
        .map_err(|e| format!("{shown}: not PEM certificates: {e}"))?;
    if certs.is_empty() {
        return Err(format!("{shown} holds no certificate"));
    }
    Ok(certs)
}

/// The subject's common name of a client's certificate (already verified by rustls
/// against the CA): the client's name in the access file.
pub fn common_name(cert: &CertificateDer<'_>) -> Option<String> {
    let (_, parsed) = x509_parser::parse_x509_certificate(cert.as_ref()).ok()?;
    let cn = parsed.subject().iter_common_name().next()?;
    cn.as_str().ok().map(str::to_string)
}
