//! `ilmrc serve --init-credentials DIR`: what a server on a network needs, made in
//! one step: a CA, the server's certificate signed by it (for `localhost`, the
//! loopback addresses and every `--san` given), a client certificate for an operator
//! (mutual TLS), tokens for a planner and an observer, and the access file naming
//! them. Secrets are written readable by their owner only.

use std::io::Write;
use std::path::{Path, PathBuf};

use rcgen::{
    BasicConstraints, CertificateParams, DnType, ExtendedKeyUsagePurpose, IsCa, Issuer, KeyPair,
    KeyUsagePurpose,
};

use super::access::TOKEN_HEX_CHARS;
use super::tls::CredentialFiles;

/// How long what is made here is valid: the CA ten years, the rest about two (the
/// longest a browser-trusted leaf may be, a common ceiling).
const CA_DAYS: i64 = 3650;
const LEAF_DAYS: i64 = 825;

/// The clients made, as `(name, role, how)`: a token file `NAME.token`, or a
/// certificate `NAME.pem` with its key `NAME.key`.
const CLIENTS: [(&str, &str, Way); 3] = [
    ("planner", "driver", Way::Token),
    ("observer", "observer", Way::Token),
    ("operator", "driver", Way::Certificate),
];

#[derive(Clone, Copy)]
enum Way {
    Token,
    Certificate,
}

/// Makes the credentials in `dir` (created if missing; refused if it holds any of the
/// files already, so that no key is overwritten). Returns what was written.
pub fn init(dir: &Path, extra_names: &[String]) -> Result<Vec<PathBuf>, String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let files = CredentialFiles::in_dir(dir);
    let mut planned = vec![
        files.ca.clone(),
        files.ca_key.clone(),
        files.server_cert.clone(),
        files.server_key.clone(),
        files.access.clone(),
    ];
    for (name, _, way) in CLIENTS {
        match way {
            Way::Token => planned.push(dir.join(format!("{name}.token"))),
            Way::Certificate => {
                planned.push(dir.join(format!("{name}.pem")));
                planned.push(dir.join(format!("{name}.key")));
            }
        }
    }
    if let Some(there) = planned.iter().find(|p| p.exists()) {
        return Err(format!(
            "{} exists already: credentials are made once (move the directory away to make new ones)",
            there.display()
        ));
    }

    let now = now()?;
    fn bad(what: &'static str) -> impl Fn(rcgen::Error) -> String {
        move |e| format!("cannot make the {what}: {e}")
    }
    let ca_key = KeyPair::generate().map_err(bad("CA's key"))?;
    let mut ca_params = CertificateParams::new(Vec::<String>::new()).map_err(bad("CA"))?;
    ca_params.is_ca = IsCa::Ca(BasicConstraints::Constrained(0));
    ca_params
        .distinguished_name
        .push(DnType::CommonName, "ilmrc serve CA");
    ca_params.key_usages = vec![
        KeyUsagePurpose::KeyCertSign,
        KeyUsagePurpose::CrlSign,
        KeyUsagePurpose::DigitalSignature,
    ];
    valid(&mut ca_params, now, CA_DAYS);
    let ca_cert = ca_params.self_signed(&ca_key).map_err(bad("CA"))?;
    let ca_pem = ca_cert.pem();
    let ca_key_pem = ca_key.serialize_pem();
    let issuer = Issuer::new(ca_params, ca_key);

    let mut names = vec![
        "localhost".to_string(),
        "127.0.0.1".to_string(),
        "::1".to_string(),
    ];
    names.extend(extra_names.iter().cloned());
    let server_key = KeyPair::generate().map_err(bad("server's key"))?;
    let mut server = CertificateParams::new(names).map_err(bad("server's certificate"))?;
    server
        .distinguished_name
        .push(DnType::CommonName, "ilmrc serve");
    server.extended_key_usages = vec![ExtendedKeyUsagePurpose::ServerAuth];
    valid(&mut server, now, LEAF_DAYS);
    let server_cert = server
        .signed_by(&server_key, &issuer)
        .map_err(bad("server's certificate"))?;

    let mut written = Vec::new();
    let mut write = |path: PathBuf, text: &str, secret: bool| -> Result<(), String> {
        write_file(&path, text, secret)?;
        written.push(path);
        Ok(())
    };
    write(files.ca.clone(), &ca_pem, false)?;
    write(files.ca_key.clone(), &ca_key_pem, true)?;
    write(files.server_cert.clone(), &server_cert.pem(), false)?;
    write(files.server_key.clone(), &server_key.serialize_pem(), true)?;

    let mut access = String::from(
        "# Who may connect to `ilmrc serve --credentials` and what each may do\n\
         # (docs/serve.md). role: \"driver\" (lines, cont, stop; one at a time, by lease)\n\
         # or \"observer\" (status, events, stop). A client proves who it is by its\n\
         # token, or by a certificate signed by ca.pem whose common name is its name.\n",
    );
    for (name, role, way) in CLIENTS {
        access.push_str(&format!(
            "\n[[client]]\nname = \"{name}\"\nrole = \"{role}\"\n"
        ));
        match way {
            Way::Token => {
                let token = token()?;
                access.push_str(&format!("token = \"{token}\"\n"));
                write(
                    dir.join(format!("{name}.token")),
                    &format!("{token}\n"),
                    true,
                )?;
            }
            Way::Certificate => {
                access.push_str("certificate = true\n");
                let key = KeyPair::generate().map_err(bad("client's key"))?;
                let mut params = CertificateParams::new(Vec::<String>::new())
                    .map_err(bad("client's certificate"))?;
                params.distinguished_name.push(DnType::CommonName, name);
                params.extended_key_usages = vec![ExtendedKeyUsagePurpose::ClientAuth];
                valid(&mut params, now, LEAF_DAYS);
                let cert = params
                    .signed_by(&key, &issuer)
                    .map_err(bad("client's certificate"))?;
                write(dir.join(format!("{name}.pem")), &cert.pem(), false)?;
                write(dir.join(format!("{name}.key")), &key.serialize_pem(), true)?;
            }
        }
    }
    write(files.access.clone(), &access, true)?;
    Ok(written)
}

/// 32 random bytes from the system's generator, as hex.
fn token() -> Result<String, String> {
    use ring::rand::SecureRandom;
    let mut bytes = [0u8; TOKEN_HEX_CHARS / 2];
    ring::rand::SystemRandom::new()
        .fill(&mut bytes)
        .map_err(|_| "the system's random generator failed".to_string())?;
    Ok(bytes.iter().map(|b| format!("{b:02x}")).collect())
}

fn now() -> Result<time::OffsetDateTime, String> {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_err(|_| "the clock is before 1970".to_string())?
        .as_secs();
    time::OffsetDateTime::from_unix_timestamp(i64::try_from(secs).unwrap_or(i64::MAX))
        .map_err(|e| format!("the clock: {e}"))
}

/// From an hour ago (a client's clock a little behind), for `days`.
fn valid(params: &mut CertificateParams, now: time::OffsetDateTime, days: i64) {
    params.not_before = now - time::Duration::hours(1);
    params.not_after = now + time::Duration::days(days);
}

/// Creates the file (never replacing one); a secret is owner-only from its creation.
fn write_file(path: &Path, text: &str, secret: bool) -> Result<(), String> {
    let mut options = std::fs::OpenOptions::new();
    options.write(true).create_new(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.mode(if secret { 0o600 } else { 0o644 });
    }
    #[cfg(not(unix))]
    let _ = secret;
    let mut file = options
        .open(path)
        .map_err(|e| format!("cannot create {}: {e}", path.display()))?;
    file.write_all(text.as_bytes())
        .map_err(|e| format!("cannot write {}: {e}", path.display()))
}
