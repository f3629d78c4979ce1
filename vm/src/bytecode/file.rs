//! The `.ilmb` file: a module as `ilmrc build` writes it and `run`, `disasm`, `serve`
//! and `shell` read it. Little-endian throughout:
//!
//! | bytes | what |
//! | --- | --- |
//! | 8 | [`MAGIC`] |
//! | 4 | format version ([`VERSION`]) |
//! | 1 + n | the toolchain that wrote it: n, then n bytes of UTF-8 (n at most [`MAX_COMPILER_NAME`]) |
//! | 8 | the payload's length |
//! | length | the tables, in postcard (`wire.rs`) |
//! | 4 | CRC-32 (IEEE) of every byte before it |
//!
//! Reading checks, in order: the magic, the version (so that a file of another version
//! says so rather than failing its checksum), the length, the checksum, the tables, and
//! then every index ([`Module::validate`]). Nothing is allocated from a length before
//! the bytes it promises are there.

use std::io::{Seek, SeekFrom, Write};

use super::limits::MAX_COMPILER_NAME;
use super::wire::{Tables, TablesRef};
use super::{Header, MAGIC_NAME, Module, ModuleError, VERSION};

/// The first bytes of every `.ilmb` file. As PNG's: a byte with the high bit set (a
/// transfer that strips it is caught), the name, CR LF (a conversion of line endings
/// is caught) and ^Z (stops `type` on DOS).
pub const MAGIC: [u8; 8] = [0x89, b'I', b'L', b'M', b'B', b'\r', b'\n', 0x1a];

/// The fixed part before the payload (with an empty toolchain name), and the checksum
/// after it.
const HEADER: usize = 8 + 4 + 1 + 8;
const TRAILER: usize = 4;

/// The `.ilmb` bytes of `module`.
pub fn encode(module: &Module) -> Vec<u8> {
    // Room for a typical statement's share, so that a large file is not copied as it
    // doubles.
    let guess = 64 * module.stmts.len() + 16 * module.code.len() + 1024;
    let mut out = std::io::Cursor::new(Vec::with_capacity(guess));
    // Writing to memory cannot fail.
    let _ = write(module, &mut out);
    out.into_inner()
}

/// Writes the `.ilmb` file of `module` to `out` as it is encoded, so that no copy of a
/// large task's file (tens of MB) is held in memory. `out` must seek: the payload's
/// length is written when it is known. Returns the file's length.
pub fn write<W: Write + Seek>(module: &Module, out: &mut W) -> std::io::Result<u64> {
    let compiler = truncated(&module.header.compiler, MAX_COMPILER_NAME);
    let start = out.stream_position()?;
    let mut header = Vec::with_capacity(HEADER + compiler.len());
    header.extend_from_slice(&MAGIC);
    header.extend_from_slice(&VERSION.to_le_bytes());
    header.push(compiler.len() as u8);
    header.extend_from_slice(compiler.as_bytes());
    let length_at = header.len();
    header.extend_from_slice(&0u64.to_le_bytes());
    out.write_all(&header)?;
    let mut failed = None;
    let stream = Stream {
        out: &mut *out,
        buf: Vec::with_capacity(STREAM_BUFFER),
        crc: crc32fast::Hasher::new(),
        len: 0,
        failed: &mut failed,
    };
    let (payload_crc, len) = match postcard::serialize_with_flavor(&TablesRef::of(module), stream) {
        Ok(done) => done,
        // The only failure of plain tables is the writer's.
        Err(e) => return Err(failed.unwrap_or_else(|| std::io::Error::other(e.to_string()))),
    };
    header[length_at..].copy_from_slice(&len.to_le_bytes());
    let mut crc = crc32fast::Hasher::new();
    crc.update(&header);
    crc.combine(&payload_crc);
    out.write_all(&crc.finalize().to_le_bytes())?;
    let end = out.stream_position()?;
    out.seek(SeekFrom::Start(start + length_at as u64))?;
    out.write_all(&len.to_le_bytes())?;
    out.seek(SeekFrom::Start(end))?;
    Ok(end - start)
}

const STREAM_BUFFER: usize = 64 * 1024;

/// postcard's output: buffered to `out`, with the payload's checksum and length.
struct Stream<'w, W: Write> {
    out: &'w mut W,
    buf: Vec<u8>,
    crc: crc32fast::Hasher,
    len: u64,
    failed: &'w mut Option<std::io::Error>,
}

impl<W: Write> Stream<'_, W> {
    fn flush(&mut self) -> postcard::Result<()> {
        self.crc.update(&self.buf);
        self.len += self.buf.len() as u64;
        if let Err(e) = self.out.write_all(&self.buf) {
            *self.failed = Some(e);
            return Err(postcard::Error::SerializeBufferFull);
        }
        self.buf.clear();
        Ok(())
    }
}

impl<W: Write> postcard::ser_flavors::Flavor for Stream<'_, W> {
    type Output = (crc32fast::Hasher, u64);

    fn try_extend(&mut self, data: &[u8]) -> postcard::Result<()> {
        if self.buf.len() + data.len() > STREAM_BUFFER {
            self.flush()?;
        }
        self.buf.extend_from_slice(data);
        Ok(())
    }

    fn try_push(&mut self, data: u8) -> postcard::Result<()> {
        self.try_extend(&[data])
    }

    fn finalize(mut self) -> postcard::Result<Self::Output> {
        self.flush()?;
        Ok((self.crc, self.len))
    }
}

/// Appends the checksum of everything so far. Public for tools and tests that change
/// a file on purpose and want it to reach the decoder rather than fail its checksum.
pub fn seal(bytes: &mut Vec<u8>) {
    let crc = crc32fast::hash(bytes);
    bytes.extend_from_slice(&crc.to_le_bytes());
}

/// `bytes` without its checksum, with the checksum recomputed: [`seal`] for a file.
pub fn reseal(bytes: &mut Vec<u8>) {
    bytes.truncate(bytes.len().saturating_sub(TRAILER));
    seal(bytes);
}

fn truncated(s: &str, max: usize) -> &str {
    let mut end = s.len().min(max);
    while !s.is_char_boundary(end) {
        end -= 1;
    }
    &s[..end]
}

/// Reads and checks an `.ilmb` file.
pub fn decode(bytes: &[u8]) -> Result<Module, ModuleError> {
    let mut r = Reader { bytes, at: 0 };
    let magic = r.take(MAGIC.len());
    if magic != Some(&MAGIC[..]) {
        return Err(not_a_module(bytes));
    }
    let version = r.u32().ok_or(short(bytes, HEADER))?;
    if version != VERSION {
        return Err(ModuleError::Version {
            found: version,
            expected: VERSION,
        });
    }
    let n = r.u8().ok_or(short(bytes, HEADER))? as usize;
    if n > MAX_COMPILER_NAME {
        return Err(ModuleError::Decode(format!(
            "the toolchain's name is {n} bytes, more than {MAX_COMPILER_NAME}"
        )));
    }
    let compiler = r.take(n).ok_or(short(bytes, HEADER + n))?;
    let len = r.u64().ok_or(short(bytes, HEADER + n))?;
    let promised = (r.at as u64)
        .saturating_add(len)
        .saturating_add(TRAILER as u64);
    if promised != bytes.len() as u64 {
        return Err(ModuleError::Length {
            promised,
            found: bytes.len() as u64,
        });
    }
    let body = bytes.len() - TRAILER;
    let stored = u32::from_le_bytes(bytes[body..].try_into().unwrap_or_default());
    let computed = crc32fast::hash(&bytes[..body]);
    if stored != computed {
        return Err(ModuleError::Checksum { stored, computed });
    }
    let compiler = std::str::from_utf8(compiler)
        .map_err(|_| ModuleError::Decode("the toolchain's name is not UTF-8".into()))?;
    let payload = &bytes[r.at..body];
    let (tables, rest): (Tables, &[u8]) = postcard::take_from_bytes(payload)
        .map_err(|e| ModuleError::Decode(format!("the tables cannot be read: {e}")))?;
    if !rest.is_empty() {
        return Err(ModuleError::Decode(format!(
            "{} byte(s) after the tables",
            rest.len()
        )));
    }
    let module = tables.into_module(Header {
        magic: MAGIC_NAME.to_string(),
        version,
        compiler: compiler.to_string(),
    });
    module.validate()?;
    Ok(module)
}

/// What the file is instead: a JSON module of the format before this one is said as
/// its version, anything else as not a module.
fn not_a_module(bytes: &[u8]) -> ModuleError {
    if bytes.starts_with(br#"{"header":{"magic":"ILMB","version":1"#) {
        ModuleError::Version {
            found: 1,
            expected: VERSION,
        }
    } else {
        ModuleError::NotModule
    }
}

fn short(bytes: &[u8], needed: usize) -> ModuleError {
    ModuleError::Length {
        promised: (needed + TRAILER) as u64,
        found: bytes.len() as u64,
    }
}

struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize) -> Option<&'a [u8]> {
        let out = self.bytes.get(self.at..self.at.checked_add(n)?)?;
        self.at += n;
        Some(out)
    }

    fn u8(&mut self) -> Option<u8> {
        self.take(1).map(|b| b[0])
    }

    fn u32(&mut self) -> Option<u32> {
        Some(u32::from_le_bytes(self.take(4)?.try_into().ok()?))
    }

    fn u64(&mut self) -> Option<u64> {
        Some(u64::from_le_bytes(self.take(8)?.try_into().ok()?))
    }
}
