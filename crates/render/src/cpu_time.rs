//! CPU time of this process (user + system, all its threads), for timing renders on a shared
//! machine, where wall time also measures whatever else runs. Linux: fields 14 and 15 (`utime`,
//! `stime`) of `/proc/self/stat`, in clock ticks of `USER_HZ` = 100 (proc(5); fixed by the
//! kernel's user ABI); elsewhere `None`. Read here rather than through a crate: the crates that
//! do this call `getrusage` with `unsafe`, which this crate forbids.

/// Clock ticks per second of `/proc/self/stat` (`USER_HZ`).
const USER_HZ: f64 = 100.0;

/// User + system CPU seconds of this process so far (10 ms resolution), if the platform tells.
pub fn process_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    parse_stat(&stat)
}

/// `utime + stime` of a `/proc/PID/stat` line, in seconds. The fields after the command name
/// (in parentheses, which may itself hold spaces and parentheses) start with field 3, `state`.
fn parse_stat(stat: &str) -> Option<f64> {
    let rest = &stat[stat.rfind(')')? + 1..];
    let mut fields = rest.split_whitespace().skip(14 - 3);
    let utime: u64 = fields.next()?.parse().ok()?;
    let stime: u64 = fields.next()?.parse().ok()?;
    Some((utime + stime) as f64 / USER_HZ)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_utime_and_stime() {
        // proc(5)'s layout: pid (comm) state ppid pgrp session tty_nr tpgid flags minflt
        // cminflt majflt cmajflt utime stime …
        let line = "4242 (a (b) c) R 1 2 3 4 5 6 7 8 9 10 250 50 0 0 20 0 1";
        assert_eq!(parse_stat(line), Some(3.0));
        assert_eq!(parse_stat("4242 (x) R 1 2"), None);
        if cfg!(target_os = "linux") {
            assert!(process_seconds().is_some());
        }
    }
}
