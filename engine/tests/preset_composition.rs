//! Presets written as another preset plus their differences give the machine data they gave
//! when written out in full. `preset_data/lathe-counter-spindle.txt` is the counter-spindle
//! lathe's text as it stood before it was composed from the 2-axis lathe (commit 1c35066).

use nctwin_engine::MachineData;
use nctwin_engine::machine_data::presets;

/// The stored data and the typed configuration of NC data text `text`.
fn data(text: &str) -> (MachineData, nctwin_engine::MachineConfig) {
    let mut md = MachineData::default();
    let cfg = md.apply_text(text).expect("the text applies");
    (md, cfg)
}

#[test]
fn the_composed_counter_spindle_lathe_has_the_data_it_had_written_out() {
    let before = include_str!("preset_data/lathe-counter-spindle.txt");
    let composed = presets::find("lathe-counter-spindle").expect("preset").text;
    let (md_before, cfg_before) = data(before);
    let (md_now, cfg_now) = data(composed);
    assert!(md_now == md_before, "the stored machine data differ");
    assert!(cfg_now == cfg_before, "the typed configurations differ");
}

#[test]
fn the_composition_keeps_the_base_lathe_apart() {
    // The counter spindle's differences do not leak into the 2-axis lathe: three channel
    // axes X, Z, SP and its finishing tool T2 (DP1 = 510, nose radius 0.4).
    let (_, lathe) = data(presets::find("lathe-2axis").expect("preset").text);
    let (_, counter) = data(presets::find("lathe-counter-spindle").expect("preset").text);
    assert_eq!(lathe.axes_len(), 3);
    assert_eq!(counter.axes_len(), 5);
    let radius = |cfg: &nctwin_engine::MachineConfig| {
        cfg.edge(2, 1).map(|e| e[nctwin_engine::machine_data::tool_orient::slot("6").unwrap()])
    };
    assert_eq!(radius(&lathe), Some(0.4));
    assert_eq!(radius(&counter), Some(0.8));
}
