//! The 33 elementary commands of Table 7, one entry each. This table is the only place
//! that knows a command's grammar, units, ranges, what it binds and its documentation.

use crate::Command;
use crate::spec::{
    Category::{self, *},
    CommandSpec, Ends, Form, Limit, ModelNames, NameSpace, Occurs, Param, ParamKind, Range, Sets,
    Syntax, Unit, VarKind,
};

const fn param(name: &'static str, kind: ParamKind, occurs: Occurs, doc: &'static str) -> Param {
    Param {
        name,
        kind,
        occurs,
        doc,
    }
}

const fn form(
    params: &'static [Param],
    min_args: u8,
    produces: VarKind,
    label: &'static str,
) -> Form {
    Form {
        params,
        min_args,
        produces,
        label,
    }
}

const fn keyword(words: &'static [&'static str]) -> ParamKind {
    ParamKind::Keyword { words }
}

const fn value(unit: Unit, range: Range) -> ParamKind {
    ParamKind::Value { unit, range }
}

const fn setting(key: &'static str, unit: Unit, range: Range) -> ParamKind {
    ParamKind::Setting { key, unit, range }
}

const ANY: Range = Range::Any;
const DEVICE: ParamKind = ParamKind::Model {
    names: ModelNames::Device,
};
const OBJECT: ParamKind = ParamKind::Model {
    names: ModelNames::Object,
};
const DIRECTION: ParamKind = keyword(&["left", "right"]);
const METRES: ParamKind = value(Unit::Metres, ANY);
const HEADING: ParamKind = value(
    Unit::Degrees,
    Range::Between {
        min: -360.0,
        max: 360.0,
        limit: Limit::Refuse,
    },
);

// One positional argument per column of the catalogue table below keeps each entry
// readable as a row; a builder would not be `const`.
#[allow(clippy::too_many_arguments)]
const fn define(
    command: Command,
    name: &'static str,
    title: &'static str,
    grammar: &'static str,
    forms: &'static [Form],
    summary: &'static str,
    doc: &'static str,
    examples: &'static [&'static str],
    section: &'static str,
) -> CommandSpec {
    spec(
        command, name, title, Define, false, grammar, forms, summary, doc, examples, section,
    )
}

#[allow(clippy::too_many_arguments)]
const fn spec(
    command: Command,
    name: &'static str,
    title: &'static str,
    category: Category,
    movement: bool,
    grammar: &'static str,
    forms: &'static [Form],
    summary: &'static str,
    doc: &'static str,
    examples: &'static [&'static str],
    section: &'static str,
) -> CommandSpec {
    CommandSpec {
        command,
        name,
        title,
        category,
        syntax: Syntax::Call,
        movement,
        holds_block: false,
        needs_device: None,
        ends: Ends::Later,
        sets: Sets::Nothing,
        grammar,
        forms,
        summary,
        doc,
        examples,
        section,
    }
}

const fn at_issue(mut s: CommandSpec) -> CommandSpec {
    s.ends = Ends::AtIssue;
    s
}

const fn at_issue_without(mut s: CommandSpec, keyword: &'static str) -> CommandSpec {
    s.ends = Ends::AtIssueWithout { keyword };
    s
}

const fn ends(mut s: CommandSpec, ends: Ends) -> CommandSpec {
    s.ends = ends;
    s
}

const fn sets(mut s: CommandSpec, sets: Sets) -> CommandSpec {
    s.sets = sets;
    s
}

const fn holds_block(mut s: CommandSpec) -> CommandSpec {
    s.holds_block = true;
    s
}

const fn needs_device(mut s: CommandSpec, device: &'static str) -> CommandSpec {
    s.needs_device = Some(device);
    s
}

const fn structural(mut s: CommandSpec) -> CommandSpec {
    s.syntax = Syntax::Structural;
    s
}

/// The catalogue, in the order of `Command` (a test keeps them in step).
pub static CATALOGUE: [CommandSpec; Command::COUNT] = [
    // ---------------------------------------------------------------- Define
    define(
        Command::MoveMode,
        "movemode",
        "MoveMode",
        "movemode ::= \"movemode\" \"(\" mode \")\"\nmode ::= wheels | rolking | parking",
        &[form(
            &[param(
                "mode",
                ParamKind::Mode {
                    words: &["wheels", "rolking", "parking"],
                    what: "movement mode",
                },
                Occurs::One,
                "wheels: an ordinary wheeled vehicle; rolking: slides the legs along the ground; parking: all joints locked",
            )],
            1,
            VarKind::Status,
            "movement mode",
        )],
        "Selects the robot's mode of movement.",
        "Sends the mode to the robot's locomotion. The modes a robot has are listed in the \
         `[IDENTIFIERS]` of its model; a robot without them (MoRo) rejects the command.",
        &["movemode(wheels)"],
        "4.5.1",
    ),
    at_issue(define(
        Command::LocMode,
        "locmode",
        "LocMode",
        "locmode ::= \"locmode\" \"(\" mode \")\"\nmode ::= automatic | scanner | gps | odo",
        &[form(
            &[param(
                "mode",
                ParamKind::Mode {
                    words: &["automatic", "scanner", "gps", "odo"],
                    what: "navigation mode",
                },
                Occurs::One,
                "automatic: chosen by the situation; scanner: laser-scanner map; gps: satellite positioning; odo: odometry only",
            )],
            1,
            VarKind::Status,
            "navigation mode",
        )],
        "Selects the navigation mode of the localisation.",
        "The modes a robot has are listed in the `[IDENTIFIERS]` of its model.",
        &["locmode(odo)"],
        "4.5.1",
    )),
    sets(
        at_issue_without(
            define(
                Command::Speed,
                "speed",
                "Speed",
                "speed ::= \"speed\" \"(\" value [\",\" \"w\"] \")\"\nvalue ::= number | variable  (-max_speed ... max_speed m/s)",
                &[form(
                    &[
                        param(
                            "value",
                            value(
                                Unit::MetresPerSecond,
                                Range::Symmetric {
                                    param: "max_speed",
                                    limit: Limit::Refuse,
                                },
                            ),
                            Occurs::One,
                            "speed in m/s; negative drives backwards",
                        ),
                        param(
                            "w",
                            keyword(&["w"]),
                            Occurs::Optional,
                            "wait: the speed is set only when the running movement command has ended",
                        ),
                    ],
                    1,
                    VarKind::Status,
                    "speed",
                )],
                "Sets the speed for the current or next movement command.",
                "Takes effect at once (or, with `w`, when the running movement command ends). The robot \
         does not move from this command alone. Without it the robot uses the model's \
         `default_speed`. Speeds beyond the model's `max_speed` are refused.",
                &["speed(0.4)", "speed(-0.5)", "speed(-0.6,w)"],
                "4.5.1",
            ),
            "w",
        ),
        Sets::Setting {
            what: "speed",
            unless: Some("w"),
        },
    ),
    sets(
        at_issue(define(
            Command::BodyPose,
            "bodypose",
            "BodyPose",
            "bodypose ::= \"bodypose\" \"(\" setting {\",\" setting} \")\"\nsetting ::= sel \"=\" value\nsel ::= \"r\" | \"p\" | \"rc\"",
            &[form(
                &[
                    param(
                        "r",
                        setting(
                            "r",
                            Unit::Degrees,
                            Range::Symmetric {
                                param: "max_roll",
                                limit: Limit::Refuse,
                            },
                        ),
                        Occurs::Optional,
                        "roll angle in degrees",
                    ),
                    param(
                        "p",
                        setting(
                            "p",
                            Unit::Degrees,
                            Range::Symmetric {
                                param: "max_pitch",
                                limit: Limit::Refuse,
                            },
                        ),
                        Occurs::Optional,
                        "pitch angle in degrees",
                    ),
                    param(
                        "rc",
                        setting(
                            "rc",
                            Unit::Metres,
                            Range::UpTo {
                                param: "max_clearance",
                                limit: Limit::Refuse,
                            },
                        ),
                        Occurs::Optional,
                        "road clearance in metres",
                    ),
                ],
                1,
                VarKind::Status,
                "body pose",
            )],
            "Sets the body's roll, pitch and road clearance.",
            "The only define command that acts at once, even when the robot stands still. The limits \
         come from the model (`max_roll`, `max_pitch`, `max_clearance`); a robot whose model has \
         none cannot take a body pose.",
            &["bodypose(r=10,p=20,rc=0.5)"],
            "4.5.1",
        )),
        Sets::Setting {
            what: "body pose",
            unless: None,
        },
    ),
    at_issue(define(
        Command::Locate,
        "locate",
        "Locate",
        "locate ::= \"locate\" \"(\" (x-value \",\" y-value \",\" h-value | \"x\" | \"y\" | \"h\") \")\"",
        &[
            form(
                &[
                    param("x", METRES, Occurs::One, "x in metres"),
                    param("y", METRES, Occurs::One, "y in metres"),
                    param(
                        "h",
                        value(
                            Unit::Degrees,
                            Range::Between {
                                min: -180.0,
                                max: 180.0,
                                limit: Limit::Refuse,
                            },
                        ),
                        Occurs::One,
                        "heading in degrees",
                    ),
                ],
                3,
                VarKind::Status,
                "set the pose",
            ),
            form(
                &[param(
                    "field",
                    keyword(&["x", "y", "h"]),
                    Occurs::One,
                    "which coordinate of the current pose to read",
                )],
                1,
                VarKind::Reading,
                "read the pose",
            ),
        ],
        "Sets the coordinate system to a pose, or reads one coordinate of the current pose.",
        "`locate(x,y,h)` sends a new pose to dead reckoning. `v = locate(x)` reads the current \
         x (or y, or h in radians) into `v`.",
        &["locate(2.5,7.8,180)", "x=locate(x)"],
        "4.5.1",
    )),
    at_issue(define(
        Command::AdvanceStop,
        "advancestop",
        "AdvanceStop",
        "advancestop ::= \"advancestop\" \"(\" distance \")\"",
        &[form(
            &[param(
                "distance",
                value(Unit::Metres, Range::NonNegative),
                Occurs::One,
                "how far before the destination to stop, in metres",
            )],
            1,
            VarKind::Status,
            "distance",
        )],
        "Stops the following movement command this far before its destination.",
        "Affects only the next movement command; like obstacle avoidance it overrides the \
         output of the movement command.",
        &["advancestop(1.0)"],
        "4.5.1",
    )),
    at_issue(define(
        Command::ObsAvoid,
        "obsavoid",
        "ObsAvoid",
        "obsavoid ::= \"obsavoid\" \"(\" mode \")\"\nmode ::= on | off | stop",
        &[form(
            &[param(
                "mode",
                keyword(&["on", "off", "stop"]),
                Occurs::One,
                "on: avoid obstacles; off: ignore them; stop: stop in front of them",
            )],
            1,
            VarKind::Status,
            "mode",
        )],
        "Selects the behaviour when an obstacle is in the way.",
        "A subsumption behaviour: when on, the area in front of the robot is checked whenever \
         the environment map is updated, and an obstacle suppresses the movement command until \
         the way back to its path is free (section 4.5.7).",
        &["obsavoid(on)"],
        "4.5.1",
    )),
    at_issue(define(
        Command::Record,
        "record",
        "Record",
        "record ::= \"record\" \"(\" filename | close \")\"",
        &[form(
            &[param(
                "path",
                ParamKind::OneOf {
                    kinds: &[
                        keyword(&["close"]),
                        ParamKind::Name {
                            space: NameSpace::Path,
                        },
                    ],
                },
                Occurs::One,
                "the path to record into, or close to stop recording",
            )],
            1,
            VarKind::Status,
            "path",
        )],
        "Records the robot's positions into a named path until `record(close)`.",
        "The recorded path can later be driven with `followpath(name)`.",
        &["record(path_1)", "record(close)"],
        "4.5.1",
    )),
    at_issue(define(
        Command::Use,
        "use",
        "Use",
        "use ::= \"use\" \"(\" abspos | goalpos \")\"",
        &[form(
            &[param(
                "start",
                keyword(&["abspos", "goalpos"]),
                Occurs::One,
                "abspos: plan from the current position; goalpos: plan from the last goal pose",
            )],
            1,
            VarKind::Status,
            "start",
        )],
        "Chooses where the next movement command plans its path from.",
        "With `goalpos` the next path starts from the destination pose of the previous movement \
         command instead of the robot's current pose, so errors do not accumulate.",
        &["use(goalpos)"],
        "4.5.1",
    )),
    at_issue(define(
        Command::SavePos,
        "savepos",
        "SavePos",
        "savepos ::= \"savepos\" \"(\" name [\",\" device] \")\"",
        &[form(
            &[
                param(
                    "name",
                    ParamKind::Name {
                        space: NameSpace::SavedPosition,
                    },
                    Occurs::One,
                    "the name for the stored position; it becomes a position variable",
                ),
                param(
                    "device",
                    DEVICE,
                    Occurs::Optional,
                    "a pointing device of the model (laser): store where it points instead",
                ),
            ],
            1,
            VarKind::Position,
            "name",
        )],
        "Saves the current position (or where a pointing device points) under a name.",
        "The name becomes a position variable usable by `gotoxy(name)` and `turn(name)`.",
        &["savepos(pos1)", "savepos(pos2,laser)"],
        "4.5.1",
    )),
    at_issue(define(
        Command::CreatePath,
        "createpath",
        "CreatePath",
        "createpath ::= \"createpath\" \"(\" name {\",\" x-value \",\" y-value} \")\"",
        &[form(
            &[
                param(
                    "name",
                    ParamKind::Name {
                        space: NameSpace::Path,
                    },
                    Occurs::One,
                    "the name for the path",
                ),
                param(
                    "xy",
                    METRES,
                    Occurs::Pairs,
                    "x and y coordinates in metres, in pairs",
                ),
            ],
            1,
            VarKind::Status,
            "path",
        )],
        "Makes a path through given coordinates.",
        "The path can then be driven with `followpath(name)`.",
        &["createpath(path1,0.0,0.0,5.0,1.0,6.0,5.0)"],
        "4.5.1",
    )),
    // -------------------------------------------------------------- Movement
    ends(
        spec(
            Command::Goahead,
            "goahead",
            "Goahead",
            Movement,
            true,
            "goahead ::= \"goahead\" \"(\" [value] \")\"\nvalue ::= number | variable  (metres)",
            &[form(
                &[param(
                    "distance",
                    METRES,
                    Occurs::Optional,
                    "metres ahead; negative goes back; without it the robot goes on until broken",
                )],
                0,
                VarKind::Movement,
                "distance",
            )],
            "Moves the robot straight ahead or back.",
            "`goahead()` without a distance keeps going until the command is broken; its variable's \
         `dist` tells how far it has gone.",
            &["goahead(-1.45)", "goahead(dist1)", "dist = goahead()"],
            "4.5.3",
        ),
        Ends::NeverBare,
    ),
    spec(
        Command::Turn,
        "turn",
        "Turn",
        Movement,
        true,
        "turn ::= \"turn\" \"(\" exact | abstract \")\"\nexact ::= \"d=\" value \",c=\" value\nabstract ::= left | right | variable",
        &[
            form(
                &[
                    param(
                        "d",
                        setting("d", Unit::Degrees, ANY),
                        Occurs::One,
                        "turning angle in degrees; positive turns left",
                    ),
                    param(
                        "c",
                        setting(
                            "c",
                            Unit::PerMetre,
                            Range::Magnitude {
                                param: "max_curvature",
                                limit: Limit::Warn,
                            },
                        ),
                        Occurs::One,
                        "turning curvature (1 / radius) in 1/m",
                    ),
                ],
                2,
                VarKind::Movement,
                "exact turn",
            ),
            form(
                &[param(
                    "direction",
                    DIRECTION,
                    Occurs::One,
                    "turn when there is room; until then follow the wall on that side",
                )],
                1,
                VarKind::Movement,
                "abstract turn",
            ),
            form(
                &[param(
                    "target",
                    ParamKind::Position,
                    Occurs::One,
                    "a variable holding a position: turn to it",
                )],
                1,
                VarKind::Movement,
                "turn to a position",
            ),
        ],
        "Turns the robot to the left or right, by an exact arc or when there is room.",
        "`turn(d=..,c=..)` follows an arc of the given angle and curvature; reversing with no \
         movement linked after it, it ends on the planned heading rather than where the arc does \
         (there is no scanner behind to line up on afterwards). `turn(left)` first \
         checks the room to turn with the scanner; if there is none it keeps its distance to \
         that side with followwall until there is; if a wall ahead comes first and still leaves no \
         room, the turn is refused with that reason. `turn(door)` turns to a found position.",
        &["turn(d=90,c=0.2)", "turn(left)", "turn(todoor)"],
        "4.5.3",
    ),
    spec(
        Command::FollowPath,
        "followpath",
        "FollowPath",
        Movement,
        true,
        "followpath ::= \"followpath\" \"(\" filename [\",\" reverse] [\",\" backwards] \")\"",
        &[form(
            &[
                param(
                    "path",
                    ParamKind::Name {
                        space: NameSpace::Path,
                    },
                    Occurs::One,
                    "a path recorded with record, made with createpath, or taught beforehand",
                ),
                param(
                    "reverse",
                    keyword(&["reverse"]),
                    Occurs::Optional,
                    "drive backwards (a negative speed has the same effect)",
                ),
                param(
                    "backwards",
                    keyword(&["backwards"]),
                    Occurs::Optional,
                    "follow the path from its end to its beginning",
                ),
            ],
            1,
            VarKind::Movement,
            "path",
        )],
        "Follows a recorded or created path.",
        "Note that the dissertation's `reverse` means driving backwards while `backwards` means \
         the path is followed from its end to its beginning.",
        &["followpath(path_1)", "followpath(path2,reverse,backwards)"],
        "4.5.3",
    ),
    ends(
        spec(
            Command::FollowWall,
            "followwall",
            "FollowWall",
            Movement,
            true,
            "followwall ::= \"followwall\" \"(\" mode [\",\" distance] \")\"\nmode ::= left | right | middle",
            &[form(
                &[
                    param(
                        "side",
                        keyword(&["left", "right", "middle"]),
                        Occurs::One,
                        "follow the wall on the left or right, or keep to the middle of two walls",
                    ),
                    param(
                        "distance",
                        value(Unit::Metres, Range::Positive),
                        Occurs::Optional,
                        "distance to the wall; the model's followwall_d when omitted",
                    ),
                ],
                1,
                VarKind::Movement,
                "wall",
            )],
            "Moves along a nearby wall, or in the middle of a corridor.",
            "The wall's line is fitted from the environment map; the robot's position is projected \
         onto it, a goal three metres ahead at the wanted distance is driven to as by gotoxy, \
         and this repeats every two metres until the command is broken. A wall ahead that ends \
         the followed wall is turned round where there is room; where there is none, the command \
         is refused with that reason rather than left standing.",
            &["followwall(middle)", "followwall(left,2.5)"],
            "4.5.3",
        ),
        Ends::Never,
    ),
    spec(
        Command::FollowTarget,
        "followtarget",
        "FollowTarget",
        Movement,
        true,
        "followtarget ::= \"followtarget\" \"(\" target \",\" distance \")\"",
        &[form(
            &[
                param(
                    "target",
                    OBJECT,
                    Occurs::One,
                    "an object of the robot model",
                ),
                param(
                    "distance",
                    value(Unit::Metres, Range::Positive),
                    Occurs::One,
                    "distance to keep to the target, in metres",
                ),
            ],
            2,
            VarKind::Movement,
            "target",
        )],
        "Follows a target seen by the camera at a distance.",
        "The camera finds the target by colour and size; the scanner measures its distance at \
         that bearing; an acceptable target becomes the goal position (Figure 33).",
        &["followtarget(user,5)"],
        "4.5.3",
    ),
    spec(
        Command::GotoXY,
        "gotoxy",
        "GotoXY",
        Movement,
        true,
        "gotoxy ::= \"gotoxy\" \"(\" x-value \",\" y-value [\",\" h-value] [\",\" \"r\"] | variable [\",\" \"r\"] \")\"",
        &[
            form(
                &[
                    param("x", METRES, Occurs::One, "x in metres"),
                    param("y", METRES, Occurs::One, "y in metres"),
                    param(
                        "h",
                        HEADING,
                        Occurs::Optional,
                        "heading at the goal in degrees",
                    ),
                    param(
                        "r",
                        keyword(&["r"]),
                        Occurs::Optional,
                        "allow backing up and turning when the path is too curved",
                    ),
                ],
                2,
                VarKind::Movement,
                "coordinates",
            ),
            form(
                &[
                    param(
                        "target",
                        ParamKind::Position,
                        Occurs::One,
                        "a variable holding a position",
                    ),
                    param(
                        "r",
                        keyword(&["r"]),
                        Occurs::Optional,
                        "allow backing up and turning when the path is too curved",
                    ),
                ],
                1,
                VarKind::Movement,
                "position variable",
            ),
        ],
        "Moves the robot to a position.",
        "Plans a Bezier reference path (equations 2-3) and follows it with the position \
         controller. With `r` the robot may back up and turn first when the path's curvature \
         exceeds what the robot can drive.",
        &["gotoxy(3,4,180)", "gotoxy(myDoor)", "gotoxy(myDoor,r)"],
        "4.5.3",
    ),
    spec(
        Command::GotoRelXY,
        "gotorelxy",
        "GotorelXY",
        Movement,
        true,
        "gotorelxy ::= \"gotorelxy\" \"(\" x-value \",\" y-value [\",\" h-value] [\",\" \"r\"] | variable [\",\" \"r\"] \")\"",
        &[
            form(
                &[
                    param("x", METRES, Occurs::One, "metres ahead of the robot"),
                    param("y", METRES, Occurs::One, "metres to the left of the robot"),
                    param(
                        "h",
                        HEADING,
                        Occurs::Optional,
                        "heading change at the goal in degrees",
                    ),
                    param(
                        "r",
                        keyword(&["r"]),
                        Occurs::Optional,
                        "allow backing up and turning when the path is too curved",
                    ),
                ],
                2,
                VarKind::Movement,
                "coordinates",
            ),
            form(
                &[
                    param(
                        "target",
                        ParamKind::Position,
                        Occurs::One,
                        "a variable whose x, y are taken relative to the robot",
                    ),
                    param(
                        "r",
                        keyword(&["r"]),
                        Occurs::Optional,
                        "allow backing up and turning when the path is too curved",
                    ),
                ],
                1,
                VarKind::Movement,
                "position variable",
            ),
        ],
        "Moves the robot to a position relative to its current pose.",
        "Equal to gotoxy except that the coordinates are in the robot's own frame.",
        &["gotorelxy(3,4,180)"],
        "4.5.3",
    ),
    spec(
        Command::Approach,
        "approach",
        "Approach",
        Movement,
        true,
        "approach ::= \"approach\" \"(\" (variable | object) [\",\" distance] \")\"",
        &[form(
            &[
                param(
                    "target",
                    ParamKind::OneOf {
                        kinds: &[ParamKind::Position, OBJECT],
                    },
                    Occurs::One,
                    "a position variable, or an object of the model to look for",
                ),
                param(
                    "distance",
                    value(Unit::Metres, Range::NonNegative),
                    Occurs::Optional,
                    "how far from the target to stop; the model's bs_security when omitted",
                ),
            ],
            1,
            VarKind::Movement,
            "target",
        )],
        "Drives up to a target and stops facing it at a distance.",
        "Table 7 names approach without giving its grammar; this toolchain defines it as a goto \
         whose goal is the target's position less the stopping distance along the line of \
         approach, re-planned while the target is tracked.",
        &["approach(door)", "approach(charger,0.3)"],
        "4.4 (Table 7)",
    ),
    // ---------------------------------------------------------------- Action
    spec(
        Command::Sensor,
        "sensor",
        "Sensor",
        Action,
        false,
        "sensor ::= \"sensor\" \"(\" sensorID [\",\" define1] [\",\" define2] [\",\" forever] \")\"\nsensorID ::= name | number\ndefine1 ::= direction | integer | object\ndefine2 ::= direction\ndirection ::= left | right",
        &[
            form(
                &[
                    param(
                        "sensor",
                        DEVICE,
                        Occurs::One,
                        "a sensor of the model, by name or number",
                    ),
                    param(
                        "object",
                        OBJECT,
                        Occurs::One,
                        "an object of the model to look for",
                    ),
                    param(
                        "side",
                        DIRECTION,
                        Occurs::Optional,
                        "look only on this side",
                    ),
                    param(
                        "forever",
                        keyword(&["forever"]),
                        Occurs::Optional,
                        "keep looking; the variable holds the latest one found",
                    ),
                ],
                2,
                VarKind::Position,
                "search",
            ),
            form(
                &[
                    param(
                        "sensor",
                        DEVICE,
                        Occurs::One,
                        "a sensor of the model, by name or number",
                    ),
                    param(
                        "which",
                        ParamKind::OneOf {
                            kinds: &[DIRECTION, value(Unit::None, Range::ReadingIndex)],
                        },
                        Occurs::Optional,
                        "the readings on one side, or one reading by index",
                    ),
                    param(
                        "forever",
                        keyword(&["forever"]),
                        Occurs::Optional,
                        "keep the variable following the sensor",
                    ),
                ],
                1,
                VarKind::Reading,
                "reading",
            ),
        ],
        "Reads a sensor, or searches for an object with it.",
        "A plain reading ends as soon as it has a value but its variable keeps following the \
         sensor, so `if(v < LowBattery)` watches it. With an object the command searches until \
         it finds one and stores its position; with `forever` it keeps searching and the \
         variable holds the latest one found. A scanner reads distances in metres: the \
         nearest of all its beams, of those on one side, or the beam of an index. Beams are \
         numbered from the rightmost, evenly over the field of view: on the 180-degree, \
         361-reading scanners of MoRo and Workpartner, reading 0 looks right, 180 straight \
         ahead and 360 left, half a degree apart.",
        &[
            "dist = sensor(scanner)",
            "dist = sensor(scanner,left)",
            "ahead = sensor(scanner,180)",
            "dist = sensor(scanner,1)",
            "dist = sensor(1,0)",
            "Mydoor = sensor(scanner,door)",
        ],
        "4.5.4",
    ),
    spec(
        Command::FindTarget,
        "findtarget",
        "FindTarget",
        Action,
        false,
        "findtarget ::= \"findtarget\" \"(\" sensorID \",\" object \")\"",
        &[form(
            &[
                param(
                    "sensor",
                    DEVICE,
                    Occurs::One,
                    "a camera or scanner of the model",
                ),
                param("object", OBJECT, Occurs::One, "an object of the model"),
            ],
            2,
            VarKind::Position,
            "search",
        )],
        "Locates an object with a camera or a scanner.",
        "Works as the search form of sensor: it ends when it finds the object and stores its \
         position in the variable.",
        &["door = findtarget(scanner,door)"],
        "4.5.4",
    ),
    sets(
        at_issue(spec(
            Command::Actuator,
            "actuator",
            "Actuator",
            Action,
            false,
            "actuator ::= \"actuator\" \"(\" actuatorID \",\" value \")\"\nactuatorID ::= name | number\nvalue ::= on | off | number",
            &[form(
                &[
                    param(
                        "actuator",
                        DEVICE,
                        Occurs::One,
                        "an actuator of the model, by name or number",
                    ),
                    param(
                        "value",
                        ParamKind::OneOf {
                            kinds: &[
                                keyword(&["on", "off"]),
                                value(Unit::None, Range::DeviceRange),
                            ],
                        },
                        Occurs::One,
                        "on, off, or a reference value within the actuator's range",
                    ),
                ],
                2,
                VarKind::Status,
                "actuator",
            )],
            "Sets an actuator directly.",
            "The value must lie within the range the model gives the actuator.",
            &["actuator(brake,on)", "actuator(leg1,90)"],
            "4.5.4",
        )),
        Sets::Device,
    ),
    needs_device(
        spec(
            Command::Manipulate,
            "manipulate",
            "Manipulate",
            Action,
            false,
            "manipulate ::= \"manipulate\" \"(\" param \")\"\nparam ::= take | leave | getball | giveball",
            &[form(
                &[param(
                    "task",
                    keyword(&["take", "leave", "getball", "giveball"]),
                    Occurs::One,
                    "the manipulation sequence to start",
                )],
                1,
                VarKind::Status,
                "task",
            )],
            "Starts a manipulation sequence and ends when the manipulator reports it done.",
            "ILMR only triggers the sequence; an external process controls the manipulator.",
            &["manipulate(take)"],
            "4.5.4",
        ),
        "manipulator",
    ),
    holds_block(spec(
        Command::Init,
        "init",
        "Init",
        Action,
        false,
        "init ::= \"init\" \"(\" [address {\",\" address}] \")\"",
        &[form(
            &[param(
                "address",
                ParamKind::Model {
                    names: ModelNames::Service,
                },
                Occurs::Many,
                "a sensor or service of the model; none initialises everything",
            )],
            0,
            VarKind::Status,
            "address",
        )],
        "Initialises sensors, services and internal variables; the block waits for it.",
        "The rest of the block does not go on until init has finished.",
        &["init()", "init(navi)"],
        "4.5.4",
    )),
    // ---------------------------------------------------------- Control flow
    structural(spec(
        Command::If,
        "if",
        "If",
        ControlFlow,
        false,
        "if ::= \"if\" \"(\" expression \")\" {commands} \"endif\"\nexpression ::= variable | comparison\ncomparison ::= operand (\"<\" | \"<=\" | \"==\" | \">\" | \">=\") operand",
        &[],
        "Runs its block once, when its condition becomes true.",
        "A guard: it does not hold its block back. Its condition is evaluated every tick from \
         when it is issued until it is true; then its body runs once, and the if ends when its \
         body has ended. A bare variable means its status.",
        &["if(dist>5.5)\n    break(goahead)\n    turn(left)\nendif"],
        "4.5.5",
    )),
    structural(spec(
        Command::While,
        "while",
        "While",
        ControlFlow,
        false,
        "while ::= \"while\" \"(\" expression \")\" {commands} \"endwhile\"",
        &[],
        "Repeats its block while its condition holds.",
        "False ends it; true starts the body; when every command started by that iteration has \
         ended, the condition is evaluated again. `v = while(..)` binds its status.",
        &[
            "loop=while(cnt<5)\n    door = sensor(scanner,door,left)\n    if(door)\n        cnt = cnt + 1\n    endif\nendwhile",
        ],
        "4.5.5",
    )),
    structural(spec(
        Command::Break,
        "break",
        "Break",
        ControlFlow,
        false,
        "break ::= \"break\" [\"(\" pattern \")\"]\npattern ::= any text",
        &[],
        "Ends the commands whose text contains a pattern; bare, stops the robot and clears all.",
        "The pattern is raw text, matched case-insensitively against each live command's \
         source text: `break(followw)`, `break(while(c))`, `break(turn(d=))`. Ending a while or \
         if ends everything inside it.",
        &["break", "break(turn(d=))"],
        "4.5.5",
    )),
    at_issue(spec(
        Command::Stop,
        "stop",
        "Stop",
        ControlFlow,
        false,
        "stop ::= \"stop\"",
        &[form(&[], 0, VarKind::Status, "stop")],
        "Brings the robot to a controlled halt and pauses movement.",
        "Movement resumes with `cont`.",
        &["stop"],
        "4.5.5",
    )),
    at_issue(spec(
        Command::Cont,
        "cont",
        "Cont",
        ControlFlow,
        false,
        "cont ::= \"cont\"",
        &[form(&[], 0, VarKind::Status, "continue")],
        "Continues what `stop` paused.",
        "",
        &["cont"],
        "4.5.5",
    )),
    holds_block(spec(
        Command::Wait,
        "wait",
        "Wait",
        ControlFlow,
        false,
        "wait ::= \"wait\" \"(\" number | variable \")\"",
        &[
            form(
                &[param(
                    "variable",
                    ParamKind::Variable,
                    Occurs::One,
                    "wait until this variable's status is 1 (a bare variable always means this)",
                )],
                1,
                VarKind::Status,
                "variable",
            ),
            form(
                &[param(
                    "seconds",
                    value(Unit::Seconds, Range::NonNegative),
                    Occurs::One,
                    "time to wait in seconds",
                )],
                1,
                VarKind::Status,
                "time",
            ),
        ],
        "Holds the rest of its block for a time, or until a variable's command has ended.",
        "Only the block it stands in waits; everything else goes on. A variable is waited on \
         until its status is 1, which an ended command sets whether it completed or was broken.",
        &["wait(4.5)", "wait(door)"],
        "4.5.5",
    )),
    structural(spec(
        Command::Check,
        "check",
        "Check",
        ControlFlow,
        false,
        "check ::= \"check\" {commands} \"checkend\"",
        &[],
        "Starts a block that is only validated, never run.",
        "Everything up to `checkend` is checked and its errors reported, but nothing is created \
         to run.",
        &["check\ngoahead(3)\nturn(left)\ncheckend"],
        "4.5.5",
    )),
    structural(spec(
        Command::Checkend,
        "checkend",
        "Checkend",
        ControlFlow,
        false,
        "checkend ::= \"checkend\"",
        &[],
        "Ends a `check` block.",
        "",
        &["checkend"],
        "4.5.5",
    )),
    at_issue(spec(
        Command::Clear,
        "clear",
        "Clear",
        ControlFlow,
        false,
        "clear ::= \"clear\" \"(\" variable \")\"",
        &[form(
            &[param(
                "variable",
                ParamKind::Variable,
                Occurs::One,
                "the variable to reset",
            )],
            1,
            VarKind::Status,
            "variable",
        )],
        "Clears a variable: all its fields back to 0.",
        "A cleared variable's status is 0 again, so `wait` and `if` on it wait anew.",
        &["clear(counter)"],
        "4.5.5",
    )),
];
