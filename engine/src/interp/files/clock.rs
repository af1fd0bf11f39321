//! The date and time the file functions show (`FILEDATE` "dd.mm.yy", `FILETIME` "hh:mm.ss").
//!
//! The engine reads no clock: a file's time is session time (seconds of IPO cycles since the
//! channel's power on) counted from 01.01.2000 00:00:00, so a run gives the same dates every
//! time.

/// `dd.mm.yy` of `seconds` after 01.01.2000.
pub fn date(seconds: u64) -> String {
    let (y, m, d) = civil(seconds / 86_400);
    format!("{d:02}.{m:02}.{:02}", y % 100)
}

/// `hh:mm.ss` of `seconds` after midnight of 01.01.2000 (the manual's format: a dot before
/// the seconds).
pub fn time(seconds: u64) -> String {
    let s = seconds % 86_400;
    format!("{:02}:{:02}.{:02}", s / 3600, s / 60 % 60, s % 60)
}

/// Year, month, day of `days` after 01.01.2000 (proleptic Gregorian calendar).
fn civil(days: u64) -> (u64, u64, u64) {
    let (mut year, mut left) = (2000, days);
    loop {
        let len = if is_leap(year) { 366 } else { 365 };
        if left < len {
            break;
        }
        left -= len;
        year += 1;
    }
    let feb = if is_leap(year) { 29 } else { 28 };
    let mut month = 1;
    for len in [31, feb, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31] {
        if left < len {
            break;
        }
        left -= len;
        month += 1;
    }
    (year, month, left + 1)
}

fn is_leap(y: u64) -> bool {
    (y.is_multiple_of(4) && !y.is_multiple_of(100)) || y.is_multiple_of(400)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dates_and_times_count_from_the_start_of_2000() {
        assert_eq!((date(0), time(0)), ("01.01.00".to_string(), "00:00.00".to_string()));
        // 2000 is a leap year: day 59 is 29 February, day 366 is 1 January 2001.
        assert_eq!(date(59 * 86_400), "29.02.00");
        assert_eq!(date(366 * 86_400), "01.01.01");
        assert_eq!(time(3 * 3600 + 25 * 60 + 7), "03:25.07");
    }
}
