//! The emergency stop under a flood (issue 19): a server at its client limit, every
//! other client sending heavy lines as fast as they are answered, and an operator's
//! new connection sending `{"stop": true}`. The stop must take its own path: the
//! robot is told to brake while the flood goes on, and the tick keeps time. The
//! bounds are generous (a loaded 2-core machine, a debug build); before the stop had
//! its own path, the tick froze for seconds under this flood and the stop waited
//! behind every line. Figures: benches/serve_flood.rs, docs/performance.md.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

use serde_json::json;

use super::{Client, Server};

/// `x=1+1+...`: 20 KB, refused by the operator limit after a full lexing.
fn heavy_line(terms: usize) -> String {
    json!({"ilmr": format!("x={}", vec!["1"; terms].join("+"))}).to_string()
}

fn speed(c: &mut Client) -> f64 {
    c.ask(r#"{"status": true}"#)["speed"]
        .as_f64()
        .unwrap_or(f64::NAN)
}

#[test]
fn a_stop_gets_through_a_full_server_flooded_with_heavy_lines() {
    let server = Server::start(&["--world", "empty"]);
    let mut driver = server.connect();
    let go = driver.ask(r#"{"ilmr": "speed(0.4)\ngoahead(1000)"}"#);
    assert_eq!(go["ok"], json!(true), "{go}");
    let deadline = Instant::now() + super::PATIENCE;
    while speed(&mut driver) < 0.3 {
        assert!(Instant::now() < deadline, "the robot never drove");
        std::thread::sleep(Duration::from_millis(20));
    }

    // With the driver, the flood fills every place the server has before it reserves.
    let running = Arc::new(AtomicBool::new(true));
    let answered = Arc::new(AtomicU64::new(0));
    let request = heavy_line(5000);
    let flooders: Vec<_> = (0..63)
        .map(|_| {
            let mut c = server.connect();
            let (running, answered, request) =
                (Arc::clone(&running), Arc::clone(&answered), request.clone());
            std::thread::spawn(move || {
                // Bounded: the test stops the flood, and every wait has a deadline.
                for _ in 0..100_000 {
                    if !running.load(Ordering::SeqCst) {
                        return;
                    }
                    let answer = c.ask(&request);
                    assert_eq!(answer["ok"], json!(false), "{answer}");
                    answered.fetch_add(1, Ordering::SeqCst);
                }
            })
        })
        .collect();
    std::thread::sleep(Duration::from_millis(1500));
    let before = driver.ask(r#"{"status": true}"#);
    let wall = Instant::now();
    let flood_before = answered.load(Ordering::SeqCst);
    assert!(flood_before > 0, "the flood is flowing");

    let mut operator = server.connect();
    let ack = operator.ask(r#"{"stop": true, "id": "e-stop"}"#);
    assert_eq!(
        (ack["ok"].clone(), ack["id"].clone()),
        (json!(true), json!("e-stop")),
        "{ack}"
    );
    let t_before = before["t"].as_f64().unwrap_or(f64::NAN);
    let t_stop = ack["t"].as_f64().unwrap_or(f64::NAN);
    // Joined at the robot's next tick or so, not after the flood's lines.
    assert!(
        t_stop - t_before < 1.0,
        "stop joined at {t_stop}, asked at {t_before}"
    );

    // The robot brakes to a halt while the flood goes on.
    let deadline = Instant::now() + super::PATIENCE;
    while speed(&mut driver).abs() > 1e-3 {
        assert!(Instant::now() < deadline, "the robot did not halt");
        std::thread::sleep(Duration::from_millis(20));
    }
    let after = driver.ask(r#"{"status": true}"#);
    assert!(
        answered.load(Ordering::SeqCst) > flood_before,
        "the flood was still answered"
    );
    running.store(false, Ordering::SeqCst);
    // Simulated time kept pace with the wall, and no tick was held up for long (a
    // frozen tick, as before, shows as a gap of seconds).
    let simulated = after["t"].as_f64().unwrap_or(0.0) - t_before;
    let elapsed = wall.elapsed().as_secs_f64();
    assert!(
        simulated > 0.5 * elapsed,
        "{simulated} s simulated in {elapsed} s"
    );
    let gap = after["longest_tick_gap"].as_f64().unwrap_or(f64::NAN);
    assert!(gap < 0.5, "a tick waited {gap} s");
    for f in flooders {
        f.join().expect("a flooder");
    }
}
