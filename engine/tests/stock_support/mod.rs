//! Running a program against a blank in the material-removal tests.

use nctwin_engine::channel::{StockInfo, StockOptions, StockWarning};
use nctwin_engine::{Channel, Event};

/// Runs `program` on `preset` (with the machine data `md`) to its end; its stock summary, the
/// checks raised and the channel. An alarm fails the test.
pub fn run(preset: &str, md: &str, options: StockOptions, program: &str) -> (StockInfo, Vec<StockWarning>, Channel) {
    let mut ch = Channel::from_preset(preset, md).unwrap();
    ch.set_stock_options(options).unwrap();
    ch.run_program(program).unwrap();
    let mut warnings = Vec::new();
    let mut cycles = 0u64;
    while ch.is_busy() {
        ch.step();
        cycles += 1;
        assert!(cycles < 5_000_000, "program does not end");
        for e in ch.take_events() {
            match e {
                Event::Stock(w) => warnings.push(w),
                Event::AlarmRaised(a) => panic!("alarm {a:?}"),
                _ => {}
            }
        }
    }
    let info = ch.stock_info().expect("a blank is defined");
    for e in ch.take_events() {
        if let Event::Stock(w) = e {
            warnings.push(w);
        }
    }
    (info, warnings, ch)
}
