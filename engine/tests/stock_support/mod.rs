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

/// The material intervals along Z of the dexel cell whose square holds (x, y) (the stock's
/// frame); panics if the stock is not dexels. Not every test file reads cells.
#[allow(dead_code)]
pub fn cell(ch: &mut Channel, x: f64, y: f64) -> Vec<[f32; 2]> {
    let Some(nctwin_engine::stock::Stock::Milling(g)) = ch.stock() else { panic!("the stock is not dexels") };
    let (x0, y0) = g.origin();
    let res = g.resolution();
    let (i, j) = (((x - x0) / res) as usize, ((y - y0) / res) as usize);
    let mut iv = Vec::new();
    g.intervals(i, j, &mut iv);
    iv
}
