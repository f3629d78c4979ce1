//! Figure 20 (section 4.1) in the office's north wing: MoRo, corrected, fetches two
//! loads and comes home; a low battery hands over to `Go_Charger`; the printed
//! figure loads once and goes the wrong way; Workpartner stops at its door; its
//! `Takebox` takes the yard's box.

use ilmr_experiments::fig20_fetch_boxes::{
    BOX, BOX_WITHIN, HEADING_WITHIN, LOW_BATTERY, Outcome, PRINTED_EAST, SHORT_OF_DOOR, START,
    corrected, low_battery, printed, takebox_in_the_yard, workpartner_in_the_office,
};

fn print(what: &str, o: &Outcome) {
    println!(
        "{what}: {} at {:.2} s, Turns {:?}, loads ended at {:?}, {:.1} m driven, \
         end ({:.2}, {:.2}, {:.1} deg), battery {:.2} V, {} completed, {} refused, contacts {}",
        if o.ended { "ended" } else { "NOT ended" },
        o.time,
        o.turns,
        o.loads,
        o.driven,
        o.end.x,
        o.end.y,
        o.end.h.to_degrees(),
        o.volts,
        o.completed,
        o.refused,
        o.contacts
    );
}

#[test]
fn moro_fetches_two_loads_and_comes_home_facing_its_door() {
    let o = corrected().expect("the corrected figure runs");
    print("Figure 20 (corrected), MoRo", &o);
    assert!(o.ended, "the task ends, only the battery guard waiting");
    assert_eq!(o.turns, Some(2.0));
    assert_eq!(o.ends("While(Turns<2)"), ["completed"], "the loop ran out");
    // Two loads: each time the box found, driven up to, the horn, the wait.
    assert_eq!(o.ends("box_at = findtarget(scanner,box)"), ["completed"; 2]);
    assert_eq!(o.ends("at_box = approach(box_at,1.35)"), ["completed"; 2]);
    assert_eq!(o.issues("actuator(horn,on)"), 2);
    assert_eq!(o.issues("actuator(horn,off)"), 2);
    assert_eq!(o.ends("wait(20)"), ["completed"; 2]);
    assert_eq!(o.actuators, [("horn".to_string(), 0.0)]);
    let (bx, by) = o.box_at.expect("box_at is a variable");
    assert!(
        (bx - BOX.0).hypot(by - BOX.1) < BOX_WITHIN,
        "the store room's box: {:?}",
        o.box_at
    );
    // Each trip found its way home: its own door, seen from the hall.
    assert_eq!(
        o.ends("Door=sensor(scanner,door,left,forever)"),
        ["broken"; 2]
    );
    // Turn(Door) twice a trip: into the store room and into its own room.
    assert_eq!(o.ends("Turn(Door)"), ["completed"; 4]);
    assert!(o.in_room_h(), "back in its room: {:?}", o.end);
    assert!(
        (o.end.h.to_degrees() - START.2).abs() < HEADING_WITHIN,
        "facing its door: {:?}",
        o.end
    );
    assert_eq!(o.contacts, 0, "no contact");
    // The battery never ran low, so the battery branch never took over.
    assert_eq!(o.issues("Priority=Highest"), 0);
    assert!(o.battery.expect("Battery is a variable") > LOW_BATTERY);
}

#[test]
fn a_low_battery_ends_everything_and_sends_moro_to_its_charger() {
    let l = low_battery().expect("the low-battery run runs");
    let o = &l.outcome;
    let low = o.battery.expect("Battery is a variable");
    println!(
        "battery {low:.2} V: While {:?}, Followwall {:?}, go_charger search issued {}, speed {:.3}",
        o.ends("While(Turns<2)"),
        o.ends("Followwall(middle)"),
        o.issues("charger_spot = findtarget(scanner,charger)"),
        l.speed
    );
    assert!(!l.priority_before, "out in the hall on the first trip");
    assert!(low < LOW_BATTERY, "below LowBattery: {low}");
    assert!(o.issues("Priority=Highest") > 0);
    // Priority=Highest ends every other command: the loop and what it drove.
    assert_eq!(o.ends("While(Turns<2)"), ["broken"]);
    assert_eq!(o.turns, Some(0.0));
    // Go_Charger (built in) looks for the charging station with the scanner.
    assert!(o.issues("charger_spot = findtarget(scanner,charger)") > 0);
    assert_eq!(o.contacts, 0);
}

#[test]
fn the_printed_figure_loads_once_then_leaves_the_corridor_the_wrong_way() {
    let o = printed().expect("the printed figure runs");
    print("Figure 20 as printed, MoRo", &o);
    // Out, along, in, loaded, and back out along the recorded path...
    assert_eq!(o.ends("wait(20)"), ["completed"]);
    assert_eq!(o.ends("Followpath(ToDoor,backwards)"), ["completed"]);
    assert_eq!(o.ends("Turnok=Turn(d=-90,c=1)"), ["completed"]);
    // ...but reversing right leaves it across the hall, and followwall takes it
    // on away from its door: its own door is never seen on the left again.
    assert_eq!(o.issues("Break(sensor)"), 0, "MyDoor never found again");
    assert_eq!(o.turns, Some(0.0));
    assert!(
        o.end.x > START.0 + PRINTED_EAST,
        "far east of its door: {:?}",
        o.end
    );
    assert_eq!(o.contacts, 0);
}

#[test]
fn workpartner_does_not_get_through_its_office_door() {
    let w = workpartner_in_the_office().expect("Workpartner runs");
    let o = &w.outcome;
    println!(
        "Workpartner in the office: {:?}, end ({:.2}, {:.2}, {:.1} deg), {:.2} m driven",
        w.stopped,
        o.end.x,
        o.end.y,
        o.end.h.to_degrees(),
        o.driven
    );
    assert!(w.stopped.is_some(), "stopped at the door");
    assert!(
        o.in_room_h() && o.end.y < SHORT_OF_DOOR,
        "still in its room: {:?}",
        o.end
    );
    assert_eq!(o.turns, Some(0.0));
    assert_eq!(o.contacts, 0);
}

#[test]
fn workpartner_takes_a_box_with_its_takebox_in_the_yard() {
    let y = takebox_in_the_yard().expect("the yard run runs");
    println!(
        "Workpartner's Takebox in the yard: ended {} at {:.2} s, carrying {:?}",
        y.outcome.ended, y.outcome.time, y.carrying
    );
    assert!(y.outcome.ended, "Takebox ends");
    assert_eq!(y.outcome.ends("taken = manipulate(take)"), ["completed"]);
    assert_eq!(y.carrying.as_deref(), Some("box1"));
    assert_eq!(y.outcome.contacts, 0);
}
