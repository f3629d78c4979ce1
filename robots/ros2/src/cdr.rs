//! A message as DDS carries it in a sample: the RTPS encapsulation header (CDR, big or
//! little endian, options 0), then the plain-CDR body, aligned from the body's start.

use byteorder::{BigEndian, LittleEndian};

use crate::msg::RosMessage;

/// The largest sample accepted, bytes: a LaserScan of 100,000 beams with intensities
/// is 0.8 MB; ten times that is no scanner's.
pub const MAX_MESSAGE_BYTES: usize = 8 << 20;

/// `CDR_BE` and `CDR_LE` (DDSI-RTPS 2.3, 10.5).
const CDR_BE: [u8; 2] = [0x00, 0x00];
const CDR_LE: [u8; 2] = [0x00, 0x01];

#[derive(Debug, Clone, PartialEq)]
pub enum DecodeError {
    TooLarge {
        bytes: usize,
    },
    /// Shorter than the encapsulation header.
    NoHeader,
    /// An encapsulation this reader does not take (XCDR2, PL_CDR ...).
    Encapsulation([u8; 2]),
    /// The body does not hold the message `type_name`.
    Body {
        type_name: &'static str,
        reason: String,
    },
}

impl std::fmt::Display for DecodeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            DecodeError::TooLarge { bytes } => write!(
                f,
                "a sample of {bytes} bytes is above the limit of {MAX_MESSAGE_BYTES} (MAX_MESSAGE_BYTES)"
            ),
            DecodeError::NoHeader => {
                write!(f, "a sample shorter than its 4-byte encapsulation header")
            }
            DecodeError::Encapsulation(id) => write!(
                f,
                "encapsulation {:02x}{:02x} is not plain CDR (0000 or 0001)",
                id[0], id[1]
            ),
            DecodeError::Body { type_name, reason } => {
                write!(f, "not a {type_name}: {reason}")
            }
        }
    }
}

impl std::error::Error for DecodeError {}

/// The byte order of a CDR body, from its encapsulation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Order {
    Little,
    Big,
}

/// The sample DDS sends for `message`: little-endian CDR, as every ROS 2 RMW writes
/// on x86 and ARM.
pub fn encode<M: RosMessage>(message: &M) -> Vec<u8> {
    let mut out = Vec::with_capacity(64);
    out.extend_from_slice(&CDR_LE);
    out.extend_from_slice(&[0, 0]);
    out.extend_from_slice(&encode_body(message));
    out
}

/// The little-endian CDR body of `message`, without the encapsulation header (DDS
/// writers put the header in themselves).
pub fn encode_body<M: RosMessage>(message: &M) -> Vec<u8> {
    // Serialising a plain struct into a Vec cannot fail: the serializer errors only on
    // shapes these types do not have (maps, untagged enums).
    match cdr_encoding::to_vec::<M, LittleEndian>(message) {
        Ok(body) => body,
        Err(e) => unreachable!("{} has no CDR form: {e}", M::DDS_TYPE_NAME),
    }
}

/// The message in a sample, of either byte order.
pub fn decode<M: RosMessage>(sample: &[u8]) -> Result<M, DecodeError> {
    if sample.len() > MAX_MESSAGE_BYTES {
        return Err(DecodeError::TooLarge {
            bytes: sample.len(),
        });
    }
    let (header, body) = sample.split_at_checked(4).ok_or(DecodeError::NoHeader)?;
    let order = match [header[0], header[1]] {
        CDR_LE => Order::Little,
        CDR_BE => Order::Big,
        other => return Err(DecodeError::Encapsulation(other)),
    };
    decode_body(body, order)
}

/// The message in a CDR body whose encapsulation the caller has read.
pub fn decode_body<M: RosMessage>(body: &[u8], order: Order) -> Result<M, DecodeError> {
    if body.len() > MAX_MESSAGE_BYTES {
        return Err(DecodeError::TooLarge { bytes: body.len() });
    }
    let decoded = match order {
        Order::Little => cdr_encoding::from_bytes::<M, LittleEndian>(body),
        Order::Big => cdr_encoding::from_bytes::<M, BigEndian>(body),
    };
    decoded
        .map(|(message, _)| message)
        .map_err(|e| DecodeError::Body {
            type_name: M::DDS_TYPE_NAME,
            reason: e.to_string(),
        })
}
