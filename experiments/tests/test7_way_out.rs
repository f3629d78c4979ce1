//! Test 7 (Figures 58-59): MoRo finds the lab door, completes the way out, and the
//! path it recorded drives again from the start.

use ilmr_experiments::test7_way_out::{
    DOOR, DOOR_WITHIN, LOBBY, PATH_POINTS, REPLAY_MISS, REPLAY_OFF, run,
};

#[test]
fn figure_58_finds_the_door_completes_and_its_path_drives_again() {
    let t = run().expect("test 7 runs");
    let w = &t.way_out;
    let (dx, dy, dh) = w.door;
    let end = w.end;
    println!(
        "test 7: {} in {:.1} s, {:.1} m driven, door seen at ({dx:.3}, {dy:.3}) heading {:.1} deg, \
         end ({:.2}, {:.2}, {:.1} deg), path_1 {} points, contacts {}",
        if w.finished {
            "completed"
        } else {
            "NOT completed"
        },
        w.time,
        w.driven,
        dh.to_degrees(),
        end.x,
        end.y,
        end.h.to_degrees(),
        w.path_1.len(),
        w.contacts
    );
    for (text, how) in &w.ends {
        println!("  {text}: {how:?}");
    }
    assert!(w.finished, "the task completes");
    assert_eq!(w.contacts, 0, "no contact on the way");
    assert!(
        (dx - DOOR.0).abs() < DOOR_WITHIN && (dy - DOOR.1).abs() < DOOR_WITHIN,
        "the lab door: {:?}",
        w.door
    );
    assert_eq!(w.how("gotoxy(door)"), Some("completed"));
    assert_eq!(w.how("goahead(1)"), Some("completed"));
    // Out of the lab, down the west corridor and into the lobby.
    assert!(end.y < LOBBY.1 && end.x > LOBBY.0, "in the lobby: {end:?}");
    assert!(w.path_1.len() > PATH_POINTS, "path_1 recorded");

    // Driven again from the start, as the dissertation did.
    let r = &t.replay;
    println!(
        "followpath(path_1): {} in {:.1} s, at most {:.3} m off the recorded path, \
         ends {:.3} m from its end, contacts {}",
        r.how.as_deref().unwrap_or_default(),
        r.time,
        r.off,
        r.miss,
        r.contacts
    );
    assert_eq!(r.how.as_deref(), Some("completed"));
    assert_eq!(r.contacts, 0);
    assert!(r.off < REPLAY_OFF, "stays on the recorded path: {}", r.off);
    assert!(r.miss < REPLAY_MISS, "ends where it was taught: {}", r.miss);
}
