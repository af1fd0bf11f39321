//! Transformation data sets: `$MC_TRAFO_TYPE_n`, `$MC_TRAFO_AXES_IN_n`,
//! `$MC_TRAFO_GEOAX_ASSIGN_TAB_n`, `$MC_TRAFO_INCLUDES_TOOL_n` (n = 1..10) and the
//! TRANSMIT_/TRACYL_/TRAANG_/TRAFO5_ data of each kind, typed and checked once at activation so
//! that selecting a transformation in a program can only fail for reasons the program controls.
//!
//! The k-th data set of one kind (counted in data-set order) uses that kind's data with suffix
//! `_k`; the control has two of each (`TRANSMIT(2)` is the 2nd TRANSMIT data set). The
//! orientation transformations (TRAORI) are decoded in [`super::traori`].

use super::MachineData;
use super::config::{ActivationError, ChannelAxis, MachineAxis};
use super::registry::MAX_TRAFO_SETS;
use super::traori::{self, TraoriParams};

/// The kinematic transformations this product models.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TrafoKind {
    /// Face-end transformation, types 256 and 257.
    Transmit,
    /// Cylinder-surface transformation, types 512, 513 and 514.
    Tracyl,
    /// Inclined axis, type 1024.
    Traang,
    /// Orientation transformation (3-, 4-, 5-, 6-axis, generic, cardan head), types 16..255.
    Traori,
    /// Chained transformation, type 8192: two data sets one after the other (the second a TRAANG).
    Tracon,
}

impl TrafoKind {
    /// The kind of a `$MC_TRAFO_TYPE_n` value, if modelled.
    pub fn of_type(trafo_type: u32) -> Option<TrafoKind> {
        match trafo_type {
            256 | 257 => Some(TrafoKind::Transmit),
            512..=514 => Some(TrafoKind::Tracyl),
            1024 => Some(TrafoKind::Traang),
            // Every code of the orientation range; `traori::decode` explains the ones it rejects.
            16..=255 => Some(TrafoKind::Traori),
            8192 => Some(TrafoKind::Tracon),
            _ => None,
        }
    }

    /// The NC word that selects the kind.
    pub fn name(self) -> &'static str {
        match self {
            TrafoKind::Transmit => "TRANSMIT",
            TrafoKind::Tracyl => "TRACYL",
            TrafoKind::Traang => "TRAANG",
            TrafoKind::Traori => "TRAORI",
            TrafoKind::Tracon => "TRACON",
        }
    }

    fn prefix(self) -> &'static str {
        match self {
            TrafoKind::Transmit => "$MC_TRANSMIT_",
            TrafoKind::Tracyl => "$MC_TRACYL_",
            TrafoKind::Traang => "$MC_TRAANG_",
            TrafoKind::Traori => "$MC_TRAFO5_",
            TrafoKind::Tracon => "$MC_TRACON_",
        }
    }
}

/// The kind-specific data of one data set.
#[derive(Debug, Clone, PartialEq)]
pub enum TrafoParams {
    Transmit {
        /// `TRANSMIT_ROT_AX_OFFSET_t`, degrees.
        rot_offset: f64,
        /// `TRANSMIT_ROT_AX_FRAME_t`: 0 = the rotary axis' axial offset stays outside, 1/2 = it
        /// is taken into the transformation.
        rot_frame: u8,
        /// `TRANSMIT_ROT_SIGN_IS_PLUS_t`.
        sign_plus: bool,
        /// `TRANSMIT_POLE_SIDE_FIX_t`: 0 free, 1 radial axis positive, 2 negative.
        pole_side_fix: u8,
        /// `TRANSMIT_BASE_TOOL_t[0..2]`.
        base_tool: [f64; 3],
    },
    Tracyl {
        rot_offset: f64,
        rot_frame: u8,
        /// `TRACYL_DEFAULT_MODE_t`: groove-wall offset of type 514 when TRACYL gives no 3rd parameter.
        default_mode: u8,
        sign_plus: bool,
        base_tool: [f64; 3],
    },
    Traang {
        /// `TRAANG_ANGLE_t`, degrees; the programmed angle of TRAANG(α) overrides it.
        angle: f64,
        base_tool: [f64; 3],
        /// `TRAANG_PARALLEL_VELO_RES_t` and `..._ACCEL_RES_t`: share of the parallel axis' velocity
        /// and acceleration kept for the compensating motion.
        velo_reserve: f64,
        accel_reserve: f64,
    },
    /// Boxed: the orientation data are several times larger than the other kinds'.
    Traori(Box<TraoriParams>),
    /// `TRACON_CHAIN_t[0..1]`: the data-set numbers of the two members, BCS side first.
    Tracon { members: [usize; 2] },
}

/// One configured transformation data set.
#[derive(Debug, Clone, PartialEq)]
pub struct TrafoDataSet {
    /// Data-set number n of `$MC_TRAFO_TYPE_n` (1..10).
    pub number: usize,
    pub trafo_type: u32,
    pub kind: TrafoKind,
    /// Which data set of its kind this is (1 or 2): the `_t` suffix of its kind's data and the
    /// `n` of `TRANSMIT(n)`.
    pub kind_index: usize,
    /// Channel axis (0-based index into `MachineConfig::channel_axes`) per role of
    /// `TRAFO_AXES_IN_n`; `None` for a 0 entry. Roles are described per kind in `kinematics`
    /// (TRAORI: [0..2] linear axes, [3] 1st, [4] 2nd, [5] 3rd rotary axis, [6] the 7th axis
    /// that turns the workpiece).
    pub axes_in: [Option<usize>; 7],
    /// Channel axis of the 1st/2nd/3rd geometry axis while the transformation is active.
    pub geo_axes: [Option<usize>; 3],
    /// `TRAFO_INCLUDES_TOOL_n`: the tool length is handled inside the transformation.
    pub includes_tool: bool,
    pub params: TrafoParams,
    /// Set for a transformation defined by kinematic chains (`$NT_…`), `None` for machine data.
    pub chain: Option<ChainDef>,
}

/// What a transformation defined by kinematic chains adds to its data set.
#[derive(Debug, Clone, PartialEq)]
pub struct ChainDef {
    /// `$NT_NAME`: what `TRAFOON("name")` selects.
    pub name: String,
    /// Tens and hundreds digits of `$NT_TRAFO_INDEX`: the conventional call (`TRAORI(n)`) this
    /// transformation answers instead of the n-th machine-data set of its kind.
    pub conventional: Option<usize>,
}

fn fail<T>(datum: &'static str, message: String) -> Result<T, ActivationError> {
    Err(ActivationError { datum: Some(datum), message })
}

/// Registry names of data set n (`n` in 1..=10), as static strings for error attribution.
fn datum_names(n: usize) -> (&'static str, &'static str, &'static str) {
    const TYPE: [&str; MAX_TRAFO_SETS] = [
        "TRAFO_TYPE_1",
        "TRAFO_TYPE_2",
        "TRAFO_TYPE_3",
        "TRAFO_TYPE_4",
        "TRAFO_TYPE_5",
        "TRAFO_TYPE_6",
        "TRAFO_TYPE_7",
        "TRAFO_TYPE_8",
        "TRAFO_TYPE_9",
        "TRAFO_TYPE_10",
    ];
    const AXES: [&str; MAX_TRAFO_SETS] = [
        "TRAFO_AXES_IN_1",
        "TRAFO_AXES_IN_2",
        "TRAFO_AXES_IN_3",
        "TRAFO_AXES_IN_4",
        "TRAFO_AXES_IN_5",
        "TRAFO_AXES_IN_6",
        "TRAFO_AXES_IN_7",
        "TRAFO_AXES_IN_8",
        "TRAFO_AXES_IN_9",
        "TRAFO_AXES_IN_10",
    ];
    const GEO: [&str; MAX_TRAFO_SETS] = [
        "TRAFO_GEOAX_ASSIGN_TAB_1",
        "TRAFO_GEOAX_ASSIGN_TAB_2",
        "TRAFO_GEOAX_ASSIGN_TAB_3",
        "TRAFO_GEOAX_ASSIGN_TAB_4",
        "TRAFO_GEOAX_ASSIGN_TAB_5",
        "TRAFO_GEOAX_ASSIGN_TAB_6",
        "TRAFO_GEOAX_ASSIGN_TAB_7",
        "TRAFO_GEOAX_ASSIGN_TAB_8",
        "TRAFO_GEOAX_ASSIGN_TAB_9",
        "TRAFO_GEOAX_ASSIGN_TAB_10",
    ];
    (TYPE[n - 1], AXES[n - 1], GEO[n - 1])
}

/// Reads and checks every configured data set. `resolve` maps a 1-based channel axis number to
/// its index in `channel_axes` (gaps allowed by MD11640 have no index).
pub(super) fn build(
    md: &MachineData,
    resolve: &dyn Fn(usize) -> Option<usize>,
    channel_axes: &[ChannelAxis],
    machine_axes: &[MachineAxis],
) -> Result<Vec<TrafoDataSet>, ActivationError> {
    let mut sets = Vec::new();
    let mut per_kind = [0usize; 5];
    for n in 1..=MAX_TRAFO_SETS {
        let (type_datum, axes_datum, geo_datum) = datum_names(n);
        let trafo_type = md.num(&format!("$MC_{type_datum}"), 0, 0) as u32;
        if trafo_type == 0 {
            continue;
        }
        let Some(kind) = TrafoKind::of_type(trafo_type) else {
            return fail(
                type_datum,
                format!(
                    "$MC_{type_datum}={trafo_type}: this transformation type is not modelled (orientation types 16..255, 256, 257, 512, 513, 514, 1024, 8192 are)"
                ),
            );
        };
        let slot = kind as usize;
        per_kind[slot] += 1;
        let kind_index = per_kind[slot];
        if kind_index > 2 {
            return fail(type_datum, format!("$MC_{type_datum}: at most two {} data sets per channel", kind.name()));
        }
        // Roles per kind: (role, must be rotary, required).
        let roles: &[(usize, bool, bool)] = match (kind, trafo_type) {
            (TrafoKind::Transmit, 257) => &[(0, false, true), (1, true, true), (2, false, false), (3, false, true)],
            (TrafoKind::Transmit, _) => &[(0, false, true), (1, true, true), (2, false, false)],
            (TrafoKind::Tracyl, 512) => &[(0, false, true), (1, true, true), (2, false, false)],
            (TrafoKind::Tracyl, _) => &[(0, false, true), (1, true, true), (2, false, false), (3, false, true)],
            (TrafoKind::Traang, _) => &[(0, false, true), (1, false, true), (2, false, false)],
            // Which linear and rotary roles must be present depends on the type (3-/4-axis
            // variants leave entries at 0); `traori::params` checks the combination.
            (TrafoKind::Traori, _) => &[
                (0, false, false),
                (1, false, false),
                (2, false, false),
                (3, true, false),
                (4, true, false),
                (5, true, false),
                (6, true, false),
            ],
            // A chain's axes and geometry axes are those of its members.
            (TrafoKind::Tracon, _) => &[],
        };
        let rotary = |k: usize| machine_axes[channel_axes[k].machine_axis].rotary;
        let mut axes_in = [None; 7];
        // Only the entries of the roles this type has are read (the default lists axes 1..5).
        for (i, a) in axes_in.iter_mut().enumerate().take(roles.len()) {
            let k = md.num(&format!("$MC_{axes_datum}"), 0, i) as usize;
            if k == 0 {
                continue;
            }
            *a = Some(resolve(k).ok_or_else(|| ActivationError {
                datum: Some(axes_datum),
                message: format!("$MC_{axes_datum}[{i}]={k}: channel axis {k} does not exist"),
            })?);
        }
        let mut geo_axes = [None; 3];
        for (g, a) in geo_axes.iter_mut().enumerate().filter(|_| kind != TrafoKind::Tracon) {
            let k = md.num(&format!("$MC_{geo_datum}"), 0, g) as usize;
            if k == 0 {
                continue;
            }
            *a = Some(resolve(k).ok_or_else(|| ActivationError {
                datum: Some(geo_datum),
                message: format!("$MC_{geo_datum}[{g}]={k}: channel axis {k} does not exist"),
            })?);
        }
        let assigned: Vec<usize> = geo_axes.iter().flatten().copied().collect();
        if (1..assigned.len()).any(|i| assigned[..i].contains(&assigned[i])) {
            return fail(geo_datum, format!("$MC_{geo_datum} assigns one channel axis to two geometry axes"));
        }
        for &(role, must_rotate, required) in roles {
            match axes_in[role] {
                None if required => {
                    return fail(
                        axes_datum,
                        format!("$MC_{axes_datum}[{role}] must name a channel axis for {} ({trafo_type})", kind.name()),
                    );
                }
                None => {}
                Some(k) if rotary(k) != must_rotate => {
                    return fail(
                        axes_datum,
                        format!(
                            "$MC_{axes_datum}[{role}]: channel axis {} must be a {} axis for {}",
                            channel_axes[k].name,
                            if must_rotate { "rotary" } else { "linear" },
                            kind.name()
                        ),
                    );
                }
                // The Cartesian coordinate of roles 0..2 lives in the channel axis of the role:
                // the manual's "channel axis numbers must relate to TRAFO_GEOAX_ASSIGN_TAB".
                Some(k) if role < 3 && !geo_axes.contains(&Some(k)) => {
                    return fail(
                        geo_datum,
                        format!(
                            "$MC_{geo_datum} must assign channel axis {} ($MC_{axes_datum}[{role}]) to a geometry axis",
                            channel_axes[k].name
                        ),
                    );
                }
                Some(_) => {}
            }
        }
        let roles_used: Vec<usize> = axes_in.iter().flatten().copied().collect();
        if (1..roles_used.len()).any(|i| roles_used[..i].contains(&roles_used[i])) {
            return fail(axes_datum, format!("$MC_{axes_datum} names one channel axis twice"));
        }
        for &k in &assigned {
            if rotary(k) && (kind == TrafoKind::Traori || !roles_used.contains(&k)) {
                return fail(
                    geo_datum,
                    format!("$MC_{geo_datum}: geometry axis on rotary channel axis {}", channel_axes[k].name),
                );
            }
        }
        let includes_tool = md.num(&format!("$MC_TRAFO_INCLUDES_TOOL_{n}"), 0, 0) != 0.0;
        let p = |name: &str| md.num(&format!("{}{name}_{kind_index}", kind.prefix()), 0, 0);
        let base = |name: &str| -> [f64; 3] {
            std::array::from_fn(|i| md.num(&format!("{}{name}_{kind_index}", kind.prefix()), 0, i))
        };
        let params = match kind {
            TrafoKind::Transmit => TrafoParams::Transmit {
                rot_offset: p("ROT_AX_OFFSET"),
                rot_frame: p("ROT_AX_FRAME") as u8,
                sign_plus: p("ROT_SIGN_IS_PLUS") != 0.0,
                pole_side_fix: p("POLE_SIDE_FIX") as u8,
                base_tool: base("BASE_TOOL"),
            },
            TrafoKind::Tracyl => TrafoParams::Tracyl {
                rot_offset: p("ROT_AX_OFFSET"),
                rot_frame: p("ROT_AX_FRAME") as u8,
                default_mode: p("DEFAULT_MODE") as u8,
                sign_plus: p("ROT_SIGN_IS_PLUS") != 0.0,
                base_tool: base("BASE_TOOL"),
            },
            TrafoKind::Traang => TrafoParams::Traang {
                angle: p("ANGLE"),
                base_tool: base("BASE_TOOL"),
                velo_reserve: p("PARALLEL_VELO_RES"),
                accel_reserve: p("PARALLEL_ACCEL_RES"),
            },
            TrafoKind::Traori => TrafoParams::Traori(Box::new(traori::params(
                md, trafo_type, kind_index, &axes_in, type_datum, axes_datum, resolve,
            )?)),
            TrafoKind::Tracon => {
                let members = chain_members(md, kind_index, n, &sets)?;
                geo_axes = sets.iter().find(|s| s.number == members[0]).expect("checked member").geo_axes;
                TrafoParams::Tracon { members }
            }
        };
        sets.push(TrafoDataSet {
            number: n,
            trafo_type,
            kind,
            kind_index,
            axes_in,
            geo_axes,
            includes_tool,
            params,
            chain: None,
        });
    }
    Ok(sets)
}

/// The members of the `kind_index`-th chained data set (number `n`), checked against the
/// manual's rules: two members, both defined in lower data sets, the second a TRAANG, the first
/// a TRANSMIT, TRACYL, TRAANG or TRAORI.
fn chain_members(
    md: &MachineData,
    kind_index: usize,
    n: usize,
    sets: &[TrafoDataSet],
) -> Result<[usize; 2], ActivationError> {
    const CHAIN: [&str; 2] = ["TRACON_CHAIN_1", "TRACON_CHAIN_2"];
    let datum = CHAIN[kind_index - 1];
    let members = [0, 1].map(|i| md.num(&format!("$MC_{datum}"), 0, i) as usize);
    for (i, m) in members.iter().enumerate() {
        let Some(set) = sets.iter().find(|s| s.number == *m) else {
            return fail(
                datum,
                format!("$MC_{datum}[{i}]={m}: a chain member must be a data set configured before data set {n}"),
            );
        };
        let allowed = if i == 0 { set.kind != TrafoKind::Tracon } else { set.kind == TrafoKind::Traang };
        if !allowed {
            return fail(
                datum,
                format!(
                    "$MC_{datum}[{i}]: {} cannot be the {} member of a chain (the second must be TRAANG)",
                    set.kind.name(),
                    if i == 0 { "first" } else { "second" }
                ),
            );
        }
    }
    Ok(members)
}
