//! Helpers for tests that run the real `nctwin` binary as a child process.

use std::io::{BufRead, BufReader, Read};
use std::process::Child;
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// Sends every line of stdout and stderr to one channel.
pub fn forward_lines(child: &mut Child) -> mpsc::Receiver<String> {
    let (tx, rx) = mpsc::channel();
    let stdout = child.stdout.take().expect("stdout piped");
    let stderr = child.stderr.take().expect("stderr piped");
    for reader in [Box::new(stdout) as Box<dyn Read + Send>, Box::new(stderr)] {
        let tx = tx.clone();
        std::thread::spawn(move || {
            for line in BufReader::new(reader).lines().map_while(Result::ok) {
                if tx.send(line).is_err() {
                    break;
                }
            }
        });
    }
    rx
}

/// The address (`IP:PORT`) from the server's `listening on http://...` line, waiting up to a
/// minute for it; the lines before it are dropped.
pub fn listening_address(lines: &mpsc::Receiver<String>) -> String {
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        let left = deadline.saturating_duration_since(Instant::now());
        let line = lines.recv_timeout(left).expect("a `listening on http://` line");
        if let Some((_, rest)) = line.split_once("listening on http://") {
            return rest.split_whitespace().next().expect("address").to_string();
        }
    }
}
