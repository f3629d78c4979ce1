//! Generates a large program of the shape real tasks have (searches, guards, waits,
//! counting loops, skill calls, blocks separated by empty lines), in ILMR and, line for
//! line, in Lua, so that `ilmrc check` can be measured beside `luac5.4 -p`.

// The benchmarks, the corpus writer and the parser's agreement tests each use a part.
#![allow(dead_code)]

pub struct Corpus {
    pub task: String,
    pub skills: String,
    pub lua: String,
    pub lines: usize,
}

const SKILLS: usize = 100;

pub fn generate(task_lines: usize) -> Corpus {
    let mut skills = String::new();
    let mut lua = String::new();
    for k in 0..SKILLS {
        skills.push_str(&format!(
            "skill{k}:\nspeed(-0.3)\nt{k}=turn(d=90,c=0.5)\nwait(t{k})\n\n"
        ));
        lua.push_str(&format!(
            "function skill{k}()\nspeed(-0.3)\nt{k}=turn(90,0.5)\nwait(t{k})\nend\n"
        ));
    }
    let mut task = String::new();
    let mut lines = 0;
    let mut i = 0;
    while lines < task_lines {
        let k = i % SKILLS;
        task.push_str(&format!(
            "v{i} = sensor(scanner,door,left)\nif(v{i})\n    speed(0.3)\n    g{i} = gotoxy(v{i})\n    wait(g{i})\n    skill{k}\nendif\nc{i} = 0\nwhile(c{i} < 3)\n    c{i} = c{i} + 1\nendwhile\n\n"
        ));
        lua.push_str(&format!(
            "v{i} = sensor(scanner,door,left)\nif v{i} then\n    speed(0.3)\n    g{i} = gotoxy(v{i})\n    wait(g{i})\n    skill{k}()\nend\nc{i} = 0\nwhile c{i} < 3 do\n    c{i} = c{i} + 1\nend\n\n"
        ));
        lines += 12;
        i += 1;
    }
    let lines = lines + SKILLS * 5;
    Corpus {
        task,
        skills,
        lua,
        lines,
    }
}
