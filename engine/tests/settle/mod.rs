//! Running a channel in the tests of manual operation: create it from a preset, step it until
//! nothing moves.

use nctwin_engine::Channel;

pub fn channel(preset: &str, md: &str) -> Channel {
    Channel::from_preset(preset, md).expect("preset")
}

/// Steps until nothing moves; returns the channel-axis positions of every cycle.
pub fn settle(ch: &mut Channel) -> Vec<Vec<f64>> {
    let mut samples = Vec::new();
    for _ in 0..2_000_000 {
        if !ch.is_busy() {
            return samples;
        }
        ch.step();
        samples.push(ch.axis_positions().to_vec());
    }
    panic!("the channel never came to rest");
}
