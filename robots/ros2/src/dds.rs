//! The DDS transport: a RustDDS participant, and typed writers and readers of ROS 2
//! messages on ROS 2's topic names, (de)serialised by [`crate::cdr`] so that every
//! sample read goes through the same size and shape checks as the rest of this crate.
//!
//! Nothing here blocks: writes go to RustDDS's own thread, and reads take what has
//! arrived. A reader takes at most a bounded number of samples per call, so that a
//! flooding peer costs the caller a bounded amount of time per tick.

use std::marker::PhantomData;
use std::net::Ipv4Addr;

use rustdds::no_key::{
    DataWriter, Decode, DefaultDecoder, DeserializerAdapter, SerializerAdapter, SimpleDataReader,
};
use rustdds::policy::{Durability, History, Reliability};
use rustdds::{
    DomainParticipant, DomainParticipantBuilder, Publisher, QosPolicies, QosPolicyBuilder,
    RepresentationIdentifier, Subscriber, TopicKind,
};

use crate::cdr::{self, DecodeError, Order};
use crate::msg::RosMessage;
use crate::names::TopicName;

/// The largest DDS domain id: RTPS's port mapping (7400 + 250 * domain) leaves room
/// for no more in 16-bit ports, and ROS 2 documents 0-232 on Linux.
pub const MAX_DOMAIN_ID: u16 = 232;

/// Which interfaces a participant uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reach {
    /// Every interface, as a ROS 2 node does: discovery by multicast on the LAN.
    Network,
    /// Loopback only: discovery and data stay on 127.0.0.1 (tests, and robots on the
    /// same computer).
    Loopback,
}

/// The QoS profiles this crate speaks, as ROS 2's `rclcpp` names them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Profile {
    /// `SensorDataQoS`: best effort, the last 5, volatile. A best-effort reader
    /// matches writers of either reliability, so readers use it.
    SensorData,
    /// The default profile: reliable, the last 10, volatile. A reliable writer matches
    /// readers of either reliability, so writers use it.
    Reliable,
    /// `tf_static`'s: reliable and transient local, so that a reader that comes late
    /// still gets what was published once.
    Latched,
}

impl Profile {
    fn qos(self) -> QosPolicies {
        let reliable = Reliability::Reliable {
            max_blocking_time: rustdds::Duration::from_millis(10),
        };
        let (reliability, depth, durability) = match self {
            Profile::SensorData => (Reliability::BestEffort, 5, Durability::Volatile),
            Profile::Reliable => (reliable, 10, Durability::Volatile),
            Profile::Latched => (reliable, 100, Durability::TransientLocal),
        };
        QosPolicyBuilder::new()
            .reliability(reliability)
            .history(History::KeepLast { depth })
            .durability(durability)
            .build()
    }
}

/// A failure of the transport, said for the operator.
#[derive(Debug, Clone, PartialEq)]
pub struct LinkError(pub String);

impl std::fmt::Display for LinkError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for LinkError {}

/// One DDS domain participant with a publisher and a subscriber.
pub struct Participant {
    participant: DomainParticipant,
    publisher: Publisher,
    subscriber: Subscriber,
}

impl Participant {
    pub fn join(domain_id: u16, reach: Reach) -> Result<Participant, LinkError> {
        if domain_id > MAX_DOMAIN_ID {
            return Err(LinkError(format!(
                "DDS domain {domain_id} is above {MAX_DOMAIN_ID}, the largest ROS 2 uses"
            )));
        }
        let builder = DomainParticipantBuilder::new(domain_id);
        let builder = match reach {
            Reach::Network => builder,
            Reach::Loopback => builder.with_only_networks([Ipv4Addr::LOCALHOST]),
        };
        let participant = builder
            .build()
            .map_err(|e| LinkError(format!("cannot join DDS domain {domain_id}: {e}")))?;
        let qos = QosPolicyBuilder::new().build();
        let publisher = participant
            .create_publisher(&qos)
            .map_err(|e| LinkError(format!("cannot create a DDS publisher: {e}")))?;
        let subscriber = participant
            .create_subscriber(&qos)
            .map_err(|e| LinkError(format!("cannot create a DDS subscriber: {e}")))?;
        Ok(Participant {
            participant,
            publisher,
            subscriber,
        })
    }

    pub fn domain_id(&self) -> u16 {
        self.participant.domain_id()
    }

    /// Whether a sample's writer belongs to this participant (its GUID prefix).
    pub fn is_own(&self, writer: rustdds::GUID) -> bool {
        use rustdds::RTPSEntity;
        writer.prefix == self.participant.guid().prefix
    }

    fn topic<M: RosMessage>(
        &self,
        name: &TopicName,
        profile: Profile,
    ) -> Result<rustdds::Topic, LinkError> {
        self.participant
            .create_topic(
                name.dds().to_string(),
                M::DDS_TYPE_NAME.to_string(),
                &profile.qos(),
                TopicKind::NoKey,
            )
            .map_err(|e| LinkError(format!("cannot create topic {name}: {e}")))
    }

    pub fn writer<M: RosMessage>(
        &self,
        name: &TopicName,
        profile: Profile,
    ) -> Result<Writer<M>, LinkError> {
        let topic = self.topic::<M>(name, profile)?;
        let inner = self
            .publisher
            .create_datawriter_no_key::<M, Cdr<M>>(&topic, Some(profile.qos()))
            .map_err(|e| LinkError(format!("cannot write {name}: {e}")))?;
        Ok(Writer {
            inner,
            name: name.clone(),
        })
    }

    pub fn reader<M: RosMessage + 'static>(
        &self,
        name: &TopicName,
        profile: Profile,
    ) -> Result<Reader<M>, LinkError> {
        let topic = self.topic::<M>(name, profile)?;
        let inner = self
            .subscriber
            .create_simple_datareader_no_key::<M, Cdr<M>>(&topic, Some(profile.qos()))
            .map_err(|e| LinkError(format!("cannot read {name}: {e}")))?;
        Ok(Reader {
            inner,
            name: name.clone(),
            taken: 0,
            dropped: 0,
            most: 0,
            last_error: None,
        })
    }
}

pub struct Writer<M: RosMessage> {
    inner: DataWriter<M, Cdr<M>>,
    name: TopicName,
}

impl<M: RosMessage> Writer<M> {
    pub fn send(&self, message: M) -> Result<(), LinkError> {
        self.inner
            .write(message, None)
            .map_err(|e| LinkError(format!("cannot publish on {}: {e}", self.name)))
    }

    pub fn topic(&self) -> &TopicName {
        &self.name
    }
}

/// What one [`Reader::drain`] found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Drained {
    pub taken: usize,
    /// Samples that were not a message of the topic's type (logged and dropped).
    pub dropped: usize,
}

pub struct Reader<M: RosMessage> {
    inner: SimpleDataReader<M, Cdr<M>>,
    name: TopicName,
    taken: u64,
    dropped: u64,
    /// The most samples one drain handed out or dropped.
    most: usize,
    last_error: Option<String>,
}

impl<M: RosMessage + 'static> Reader<M> {
    /// Hands `each` up to `max` samples that have arrived, oldest first; a sample that
    /// does not decode is counted, remembered and skipped.
    pub fn drain(&mut self, max: usize, mut each: impl FnMut(M)) -> Drained {
        self.drain_from(max, |m, _| each(m))
    }

    /// As [`Reader::drain`], with the GUID of the writer of each sample.
    pub fn drain_from(&mut self, max: usize, mut each: impl FnMut(M, rustdds::GUID)) -> Drained {
        let mut seen = Drained::default();
        while seen.taken + seen.dropped < max {
            match self.inner.try_take_one() {
                Ok(Some(change)) => {
                    seen.taken += 1;
                    let writer = change.writer_guid();
                    each(change.sample, writer);
                }
                Ok(None) => break,
                Err(e) => {
                    seen.dropped += 1;
                    self.last_error = Some(e.to_string());
                }
            }
        }
        self.taken += seen.taken as u64;
        self.dropped += seen.dropped as u64;
        self.most = self.most.max(seen.taken + seen.dropped);
        seen
    }

    pub fn topic(&self) -> &TopicName {
        &self.name
    }

    /// Samples taken and dropped since the reader was made.
    pub fn counts(&self) -> (u64, u64) {
        (self.taken, self.dropped)
    }

    /// The most samples one [`Reader::drain`] took or dropped.
    pub fn most_in_one_drain(&self) -> usize {
        self.most
    }

    /// Why the last dropped sample was dropped.
    pub fn last_error(&self) -> Option<&str> {
        self.last_error.as_deref()
    }
}

/// RustDDS's (de)serializer adapter for a ROS 2 message, by way of [`crate::cdr`].
pub struct Cdr<M>(PhantomData<M>);

impl<M: RosMessage> SerializerAdapter<M> for Cdr<M> {
    type Error = DecodeError;

    fn output_encoding() -> RepresentationIdentifier {
        RepresentationIdentifier::CDR_LE
    }

    fn to_bytes(value: &M) -> Result<bytes::Bytes, DecodeError> {
        Ok(bytes::Bytes::from(cdr::encode_body(value)))
    }
}

impl<M: RosMessage> DeserializerAdapter<M> for Cdr<M> {
    type Error = DecodeError;
    type Decoded = M;

    fn supported_encodings() -> &'static [RepresentationIdentifier] {
        &[
            RepresentationIdentifier::CDR_LE,
            RepresentationIdentifier::CDR_BE,
        ]
    }

    fn transform_decoded(decoded: M) -> M {
        decoded
    }
}

impl<M: RosMessage> DefaultDecoder<M> for Cdr<M> {
    type Decoder = CdrDecoder<M>;
    const DECODER: CdrDecoder<M> = CdrDecoder(PhantomData);
}

pub struct CdrDecoder<M>(PhantomData<M>);

impl<M> Clone for CdrDecoder<M> {
    fn clone(&self) -> Self {
        CdrDecoder(PhantomData)
    }
}

impl<'de, M: RosMessage> Decode<'de, M> for CdrDecoder<M> {
    type Error = DecodeError;

    fn decode_bytes(
        self,
        body: &'de [u8],
        encoding: RepresentationIdentifier,
    ) -> Result<M, DecodeError> {
        let order = if encoding == RepresentationIdentifier::CDR_LE {
            Order::Little
        } else if encoding == RepresentationIdentifier::CDR_BE {
            Order::Big
        } else {
            return Err(DecodeError::Encapsulation(encoding.to_bytes()));
        };
        cdr::decode_body(body, order)
    }
}
