//! The workload of issue 14: a task of `n` counting blocks, each with a variable of its
//! own, so that the task has `n` variables (the shape that made lowering quadratic),
//! blocks separated by an empty line so that they run together:
//!
//! ```text
//! c0=0
//! while(c0<100)
//!     c0=c0+1
//!     wait(0.01)
//! endwhile
//! ```

pub fn generate(n: usize) -> String {
    let mut task = String::with_capacity(n * 60);
    for i in 0..n {
        task.push_str(&format!(
            "c{i}=0\nwhile(c{i}<100)\n    c{i}=c{i}+1\n    wait(0.01)\nendwhile\n\n"
        ));
    }
    task
}
