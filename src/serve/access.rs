//! Who may connect and what each may do: the access file (TOML, one `[[client]]` per
//! client: its name, its role, and how it proves who it is), read once at start.
//! Tokens are secrets, so the file must be readable by its owner only, and a token is
//! compared with every client's in constant time.

use std::path::Path;

use serde::Deserialize;
use subtle::ConstantTimeEq;

/// Characters of the tokens `--init-credentials` makes (hex of 32 random bytes), and
/// the fewest a token in an access file may have.
pub const TOKEN_HEX_CHARS: usize = 64;
pub const MIN_TOKEN_CHARS: usize = 32;

/// What a client may do.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Role {
    /// Status, events and `stop`.
    Observer,
    /// Also lines and `cont`, while it holds the robot's lease.
    Driver,
}

impl Role {
    pub fn name(self) -> &'static str {
        match self {
            Role::Observer => "observer",
            Role::Driver => "driver",
        }
    }
}

/// How a client proved who it is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Proof {
    Token,
    Certificate,
    /// A server without an access file (`--no-tls` on loopback): nobody is asked.
    Nothing,
}

/// A connected client, once known.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Identity {
    pub name: String,
    pub role: Role,
    pub proof: Proof,
}

impl Identity {
    /// The client of a server that asks nobody: a driver, named by its connection.
    pub fn anonymous(conn: u64) -> Identity {
        Identity {
            name: format!("anonymous#{conn}"),
            role: Role::Driver,
            proof: Proof::Nothing,
        }
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    #[serde(default)]
    client: Vec<Client>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Client {
    name: String,
    role: Role,
    token: Option<String>,
    /// Authenticated by a client certificate whose subject's common name is `name`.
    #[serde(default)]
    certificate: bool,
}

/// The clients of an access file.
#[derive(Debug)]
pub struct Access {
    clients: Vec<Client>,
}

impl Access {
    /// Reads an access file; refuses one that others may read, or that names a client
    /// twice, gives one no way in, or holds a short token.
    pub fn load(path: &Path) -> Result<Access, String> {
        let shown = path.display();
        owner_only(path)?;
        let text = std::fs::read_to_string(path)
            .map_err(|e| format!("cannot read the access file {shown}: {e}"))?;
        Access::parse(&text).map_err(|e| format!("access file {shown}: {e}"))
    }

    pub fn parse(text: &str) -> Result<Access, String> {
        let file: File = toml::from_str(text).map_err(|e| e.message().to_string())?;
        let mut seen = std::collections::HashSet::new();
        for c in &file.client {
            if c.name.is_empty() || c.name.chars().any(char::is_control) {
                return Err(format!(
                    "client name {:?}: expected a printable name",
                    c.name
                ));
            }
            if !seen.insert(c.name.as_str()) {
                return Err(format!("client `{}` is named twice", c.name));
            }
            match &c.token {
                None if !c.certificate => {
                    return Err(format!(
                        "client `{}` has neither a token nor `certificate = true`",
                        c.name
                    ));
                }
                Some(t) if t.chars().count() < MIN_TOKEN_CHARS => {
                    return Err(format!(
                        "client `{}`: a token needs at least {MIN_TOKEN_CHARS} characters \
                         (`ilmrc serve --init-credentials` makes {TOKEN_HEX_CHARS})",
                        c.name
                    ));
                }
                _ => {}
            }
        }
        if file.client.is_empty() {
            return Err("no [[client]]: nobody could connect".into());
        }
        Ok(Access {
            clients: file.client,
        })
    }

    /// The client whose token this is. Every client's token is compared, each in
    /// constant time, so that the time taken says nothing of which one (or how much
    /// of one) matched.
    pub fn by_token(&self, token: &str) -> Option<Identity> {
        let mut found = None;
        for c in &self.clients {
            let Some(known) = &c.token else { continue };
            let same = bool::from(known.as_bytes().ct_eq(token.as_bytes()));
            if same {
                found = Some(c);
            }
        }
        found.map(|c| Identity {
            name: c.name.clone(),
            role: c.role,
            proof: Proof::Token,
        })
    }

    /// The client a verified certificate with this common name is.
    pub fn by_certificate(&self, common_name: &str) -> Option<Identity> {
        self.clients
            .iter()
            .find(|c| c.certificate && c.name == common_name)
            .map(|c| Identity {
                name: c.name.clone(),
                role: c.role,
                proof: Proof::Certificate,
            })
    }

    /// Clients named.
    pub fn len(&self) -> usize {
        self.clients.len()
    }

    pub fn wants_certificates(&self) -> bool {
        self.clients.iter().any(|c| c.certificate)
    }
}

/// A file of secrets that group or others may read is refused, as ssh refuses a key.
#[cfg(unix)]
pub fn owner_only(path: &Path) -> Result<(), String> {
    use std::os::unix::fs::PermissionsExt;
    let meta =
        std::fs::metadata(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let mode = meta.permissions().mode() & 0o777;
    if mode & 0o077 != 0 {
        return Err(format!(
            "{} holds secrets but is readable by others (mode {mode:03o}): \
             `chmod 600 {}`",
            path.display(),
            path.display()
        ));
    }
    Ok(())
}

#[cfg(not(unix))]
pub fn owner_only(_path: &Path) -> Result<(), String> {
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const PLANNER: &str = "0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef";
    const VIEWER: &str = "fedcba9876543210fedcba9876543210fedcba9876543210fedcba9876543210";

    fn access() -> Access {
        Access::parse(&format!(
            "[[client]]\nname = \"planner\"\nrole = \"driver\"\ntoken = \"{PLANNER}\"\n\
             [[client]]\nname = \"viewer\"\nrole = \"observer\"\ntoken = \"{VIEWER}\"\n\
             [[client]]\nname = \"laptop\"\nrole = \"driver\"\ncertificate = true\n"
        ))
        .expect("a valid access file")
    }

    #[test]
    fn tokens_and_certificates_name_their_clients() {
        let a = access();
        let planner = a.by_token(PLANNER).expect("the planner's token");
        assert_eq!(
            (planner.name.as_str(), planner.role),
            ("planner", Role::Driver)
        );
        assert_eq!(a.by_token(VIEWER).map(|i| i.role), Some(Role::Observer));
        assert_eq!(a.by_token(&PLANNER[1..]), None);
        assert_eq!(a.by_token(""), None);
        let mut wrong = PLANNER.to_string();
        wrong.replace_range(63.., "0");
        assert_eq!(a.by_token(&wrong), None);
        assert_eq!(
            a.by_certificate("laptop").map(|i| i.proof),
            Some(Proof::Certificate)
        );
        // A client with a token only is not let in by a certificate of its name.
        assert_eq!(a.by_certificate("planner"), None);
        assert!(a.wants_certificates());
    }

    #[test]
    fn bad_access_files_say_why() {
        let bad = |text: &str| Access::parse(text).expect_err(text);
        assert!(bad("").contains("nobody"));
        assert!(bad("[[client]]\nname = \"a\"\nrole = \"driver\"\n").contains("neither"));
        assert!(
            bad("[[client]]\nname = \"a\"\nrole = \"driver\"\ntoken = \"short\"\n")
                .contains("at least")
        );
        assert!(
            bad("[[client]]\nname = \"a\"\nrole = \"pilot\"\ncertificate = true\n")
                .contains("pilot")
        );
        let twice = "[[client]]\nname = \"a\"\nrole = \"driver\"\ncertificate = true\n";
        assert!(bad(&format!("{twice}{twice}")).contains("twice"));
        assert!(
            bad("[[client]]\nname = \"a\"\nrole = \"driver\"\ncertificate = true\nfoo = 1\n")
                .contains("foo")
        );
    }

    #[cfg(unix)]
    #[test]
    fn an_access_file_others_can_read_is_refused() {
        use std::os::unix::fs::PermissionsExt;
        let path = std::env::temp_dir().join(format!("ilmr-access-{}.toml", std::process::id()));
        std::fs::write(
            &path,
            format!("[[client]]\nname = \"p\"\nrole = \"driver\"\ntoken = \"{PLANNER}\"\n"),
        )
        .expect("write");
        std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o644)).expect("chmod");
        assert!(
            Access::load(&path)
                .expect_err("readable by others")
                .contains("chmod 600")
        );
        std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o600)).expect("chmod");
        assert!(Access::load(&path).is_ok());
        let _ = std::fs::remove_file(path);
    }
}
