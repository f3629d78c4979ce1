//! Samples a robot or a hostile peer could send: truncated, oversized, of another
//! encapsulation or another type, or with lengths that claim gigabytes. Each is an
//! error value; nothing panics or allocates beyond the sample.

use ilmr_ros2::msg::{BatteryState, LaserScan, Odometry, Twist};
use ilmr_ros2::{DecodeError, MAX_MESSAGE_BYTES, decode, encode};

#[test]
fn every_prefix_of_a_sample_is_an_error_not_a_panic() {
    let sample = encode(&LaserScan {
        ranges: vec![1.0; 10],
        ..LaserScan::default()
    });
    for n in 0..sample.len() {
        assert!(decode::<LaserScan>(&sample[..n]).is_err(), "{n} bytes");
    }
    assert!(decode::<LaserScan>(&sample).is_ok());
}

#[test]
fn a_length_that_claims_gigabytes_is_refused_without_allocating_it() {
    let mut sample = encode(&LaserScan::default());
    // The header's frame_id is empty (length 1, its NUL); the first sequence length
    // after the seven floats is `ranges`: claim four billion elements.
    let at = sample.len() - 8;
    sample[at..at + 4].copy_from_slice(&u32::MAX.to_le_bytes());
    assert!(matches!(
        decode::<LaserScan>(&sample),
        Err(DecodeError::Body { .. })
    ));
    let mut odometry = encode(&Odometry::default());
    odometry[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
    assert!(decode::<Odometry>(&odometry).is_err());
}

#[test]
fn oversized_and_foreign_samples_are_refused() {
    let big = vec![0u8; MAX_MESSAGE_BYTES + 1];
    assert_eq!(
        decode::<Twist>(&big),
        Err(DecodeError::TooLarge {
            bytes: MAX_MESSAGE_BYTES + 1
        })
    );
    let mut xcdr2 = encode(&Twist::default());
    xcdr2[1] = 0x07;
    assert_eq!(
        decode::<Twist>(&xcdr2),
        Err(DecodeError::Encapsulation([0x00, 0x07]))
    );
    assert_eq!(decode::<Twist>(&[0, 1]), Err(DecodeError::NoHeader));
    // A Twist read as a BatteryState: its strings' lengths are garbage.
    let twist = encode(&Twist::default());
    assert!(decode::<BatteryState>(&twist).is_err());
}

#[test]
fn random_bytes_never_panic() {
    let mut seed = 0x2545_f491_4f6c_dd1d_u64;
    for len in [0usize, 3, 4, 5, 16, 64, 400, 4096] {
        for _ in 0..200 {
            let bytes: Vec<u8> = (0..len)
                .map(|_| {
                    seed ^= seed << 13;
                    seed ^= seed >> 7;
                    seed ^= seed << 17;
                    seed as u8
                })
                .collect();
            let _ = decode::<Twist>(&bytes);
            let _ = decode::<Odometry>(&bytes);
            let _ = decode::<LaserScan>(&bytes);
            let _ = decode::<BatteryState>(&bytes);
        }
    }
}

#[test]
fn big_endian_samples_are_read_too() {
    // A Twist as a big-endian peer writes it: header 0000, then six doubles.
    let mut sample = vec![0, 0, 0, 0];
    for v in [0.4f64, 0.0, 0.0, 0.0, 0.0, -0.5] {
        sample.extend_from_slice(&v.to_be_bytes());
    }
    let twist = decode::<Twist>(&sample).unwrap();
    assert_eq!((twist.linear.x, twist.angular.z), (0.4, -0.5));
}
