//! The C ABI through which the Python runner (`python/mujoco/run.py`, ctypes) drives a
//! [`MujocoLanding`]: the force laws, hysteresis, energy ledger, stability criteria and outputs
//! stay in Rust, in one implementation; Python owns MuJoCo (its model and data, loaded by the
//! `mujoco` package).
//!
//! Calls, in order: [`touchdown_mujoco_open`] (scenario → runner and MJCF), then
//! [`touchdown_mujoco_model_xml`] (the model to load), [`touchdown_mujoco_bind`] (MuJoCo's
//! arrays), then the steps: [`touchdown_mujoco_run`] (the whole loop here, calling the
//! `mj_step1`/`mj_step2` of MuJoCo's library the runner hands over) or, for a loop that
//! Python keeps (the viewer's, the profiler's), [`touchdown_mujoco_advance`] once per step
//! between `mj_step1` and `mj_step2`; then [`touchdown_mujoco_finish`] (summary.json),
//! [`touchdown_mujoco_close`]. A call that fails returns a negative status (or null) and
//! leaves its message for [`touchdown_mujoco_error`]. No call panics across the boundary: a
//! panic becomes an error message.
//!
//! MuJoCo's own errors (`mju_error`: an arena too small for the step, say) never return to
//! their caller. In the library's loop they reach [`on_mujoco_message`], which writes the
//! landing's diagnostic (when, the state, MuJoCo's words) and ends the runner with the stopped
//! status; in a loop Python keeps they come back as `mujoco.FatalError`, and the runner hands
//! them to [`touchdown_mujoco_engine_error`].

use crate::landing::{GearIndex, MjArrays, ModelSizes, MujocoLanding, MUJOCO_WARNINGS};
use crate::launch::RUNNER_STOPPED_STATUS;
use crate::MujocoError;
use std::cell::Cell;
use std::ffi::{c_char, c_void, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;
use touchdown_record::History;
use touchdown_scenario::schema::Engine;
use touchdown_scenario::Scenario;

/// Pointers to MuJoCo's arrays (`MjData` and `MjModel` fields of the model loaded from
/// [`touchdown_mujoco_model_xml`]); they stay valid as long as that `MjModel`/`MjData` live.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct MjPointers {
    /// `data.qpos`.
    pub qpos: *const f64,
    /// `data.qvel`.
    pub qvel: *const f64,
    /// `data.ten_length`.
    pub ten_length: *const f64,
    /// `data.ten_velocity`.
    pub ten_velocity: *const f64,
    /// `data.site_xpos`.
    pub site_xpos: *const f64,
    /// `data.xpos`.
    pub xpos: *const f64,
    /// `data.sensordata`.
    pub sensordata: *const f64,
    /// `data.energy`.
    pub energy: *const f64,
    /// `data.warning[0].number`.
    pub warning_number: *const i32,
    /// Distance between two warnings' `number`, in `i32` elements (2 for `mjWarningStat`).
    pub warning_stride: i32,
    /// `data.ctrl`.
    pub ctrl: *mut f64,
    /// The stroke joints' dry-friction bounds, one per gear (an array of the runner's, which it
    /// copies into MuJoCo's friction rows before `mj_step2`).
    pub friction_bound: *mut f64,
    /// `data.qfrc_applied`.
    pub qfrc_applied: *mut f64,
    /// `data.xfrc_applied`.
    pub xfrc_applied: *mut f64,
}

/// `mj_step1` or `mj_step2` of the MuJoCo library the runner loaded: `void (const mjModel*,
/// mjData*)`.
pub type MjHalfStep = unsafe extern "C" fn(*const c_void, *mut c_void);

/// MuJoCo's structured log message (`mjLogMessage` in the pinned MuJoCo's
/// `include/mujoco/mjtype.h`), what its log handlers get.
#[repr(C)]
#[derive(Debug)]
pub struct MjLogMessage {
    /// `mjtLogLevel`: 0 debug, 1 info, 2 warning, 3 error ([`MJ_LOG_ERROR`]).
    pub level: i32,
    /// `mjtLogTopic` (0 for errors and warnings).
    pub topic: i32,
    /// The one-line subject, NUL-terminated.
    pub subject: [c_char; 1024],
    /// Multi-line detail, or null.
    pub body: *const c_char,
    /// The MuJoCo function that logged it, or null.
    pub func: *const c_char,
    /// MuJoCo's source file, or null.
    pub file: *const c_char,
    /// MuJoCo's source line, or 0.
    pub line: i32,
    /// Whether to prepend a time stamp (`mjtBool`).
    pub timestamp: u8,
}

/// `mjLOG_ERROR`: a message after which MuJoCo expects its handler not to return.
pub const MJ_LOG_ERROR: i32 = 3;

/// A MuJoCo log handler, `mjfLogHandler`: `void (const mjLogMessage*)`.
pub type MjLogHandler = unsafe extern "C" fn(*const MjLogMessage);

/// `mju_setLogHandler` of the MuJoCo library the runner loaded: sets the global log handler
/// and returns the one it replaces (MuJoCo's default when none was set).
pub type MjSetLogHandler = unsafe extern "C" fn(Option<MjLogHandler>) -> Option<MjLogHandler>;

/// Byte offset of the pointer `efc_frictionloss` in `mjData` of the pinned MuJoCo
/// (python/requirements.txt; `offsetof(mjData, efc_frictionloss)` in the wheel's
/// `include/mujoco/mjdata.h`). `mj_step1` places the constraint rows anew each step, so the
/// loop reads the pointer from there each step; [`touchdown_mujoco_run`] first checks it
/// against the address MuJoCo's own bindings give.
pub const EFC_FRICTIONLOSS_OFFSET: usize = 161_568;

/// What [`touchdown_mujoco_run`] steps: MuJoCo's half-steps, its model and data, and where the
/// stroke joints' friction rows are.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct MjLoop {
    /// `mj_step1` of the library that loaded `model`.
    pub step1: Option<MjHalfStep>,
    /// `mj_step2` of the same library.
    pub step2: Option<MjHalfStep>,
    /// The `mjModel*` of the bound model.
    pub model: *const c_void,
    /// The `mjData*` of the bound model.
    pub data: *mut c_void,
    /// `data.efc_frictionloss` as the bindings read it after an `mj_step1` (the check of
    /// [`EFC_FRICTIONLOSS_OFFSET`]).
    pub frictionloss: *const f64,
    /// The first of the stroke joints' friction rows, one per gear in gear order.
    pub first_row: usize,
    /// `mju_setLogHandler` of the same library: the loop routes MuJoCo's errors to
    /// [`on_mujoco_message`] while it steps.
    pub set_log_handler: Option<MjSetLogHandler>,
    /// Where [`on_mujoco_message`] writes the diagnostic of a MuJoCo error (the runner's
    /// `divergence.json`), NUL-terminated.
    pub divergence_path: *const c_char,
}

/// Where MuJoCo's messages go while [`Runner::run`] steps: the landing whose state a
/// diagnostic reports, the file it is written to, and the handler MuJoCo had before, which
/// still gets every message but the errors.
#[derive(Debug, Clone, Copy)]
struct ErrorSink {
    landing: *const MujocoLanding,
    path: *const c_char,
    previous: Option<MjLogHandler>,
}

thread_local! {
    /// This thread's [`ErrorSink`], while [`Runner::run`] steps.
    static ERROR_SINK: Cell<Option<ErrorSink>> = const { Cell::new(None) };
}

/// The log handler of [`Runner::run`]'s loop. A message below an error goes to the handler
/// MuJoCo had before (its warnings still land in `MUJOCO_LOG.TXT`, which the runner reads). An
/// error, after which MuJoCo must not resume, ends the runner: the landing's diagnostic
/// ([`MujocoLanding::engine_error`]) is written to the sink's file and said on standard error,
/// and the process exits with [`RUNNER_STOPPED_STATUS`] (1 if the file cannot be written), as
/// the runner does for any stopped landing. Nothing unwinds through MuJoCo.
///
/// # Safety
/// Called by MuJoCo with a valid message, on the thread of [`Runner::run`].
pub unsafe extern "C" fn on_mujoco_message(msg: *const MjLogMessage) {
    let (Some(sink), Some(m)) = (ERROR_SINK.with(Cell::get), msg.as_ref()) else {
        return;
    };
    if m.level != MJ_LOG_ERROR {
        if let Some(previous) = sink.previous {
            previous(msg);
        }
        return;
    }
    let status = catch_unwind(AssertUnwindSafe(|| {
        let subject = std::slice::from_raw_parts(m.subject.as_ptr().cast::<u8>(), m.subject.len());
        let mut what = match CStr::from_bytes_until_nul(subject) {
            Ok(c) => c.to_string_lossy().into_owned(),
            Err(_) => String::from_utf8_lossy(subject).into_owned(),
        };
        if !m.func.is_null() {
            what = format!("{}: {what}", CStr::from_ptr(m.func).to_string_lossy());
        }
        if !m.body.is_null() {
            what = format!(
                "{what} ({})",
                CStr::from_ptr(m.body).to_string_lossy().trim()
            );
        }
        let Some(landing) = sink.landing.as_ref() else {
            eprintln!("run.py: MuJoCo stopped with an error before the landing was bound: {what}");
            return 1;
        };
        let divergence = landing.engine_error(&what);
        eprintln!("run.py: {divergence}");
        let path = CStr::from_ptr(sink.path).to_string_lossy().into_owned();
        let written = serde_json::to_string(&divergence)
            .map_err(|e| e.to_string())
            .and_then(|json| std::fs::write(&path, json).map_err(|e| e.to_string()));
        match written {
            Ok(()) => RUNNER_STOPPED_STATUS,
            Err(e) => {
                eprintln!("run.py: cannot write the diagnostic {path}: {e}");
                1
            }
        }
    }))
    .unwrap_or(1);
    std::process::exit(status);
}

/// MuJoCo's log handler as [`Runner::run`]'s loop sets it, restored when dropped.
struct LogHandlerSet {
    set: MjSetLogHandler,
    previous: Option<MjLogHandler>,
}

impl Drop for LogHandlerSet {
    fn drop(&mut self) {
        ERROR_SINK.with(|s| s.set(None));
        // SAFETY: `set` is the library's mju_setLogHandler and `previous` what it returned.
        unsafe {
            (self.set)(self.previous);
        }
    }
}

/// A runner's state behind the C ABI.
pub struct Runner {
    scenario: Option<Scenario>,
    xml: Option<CString>,
    landing: Option<MujocoLanding>,
    pointers: Option<MjPointers>,
    error: Option<CString>,
    /// The last call's divergence as JSON (`touchdown_record::Divergence`), if it stopped the
    /// landing.
    divergence: Option<CString>,
}

impl Runner {
    fn fail(&mut self, message: String) -> i32 {
        self.error = Some(CString::new(message.replace('\0', " ")).unwrap_or_default());
        -1
    }

    /// Runs `f`, turning an error or a panic into this runner's error message and status −1.
    fn guard(&mut self, f: impl FnOnce(&mut Runner) -> Result<i32, MujocoError>) -> i32 {
        self.error = None;
        self.divergence = None;
        match catch_unwind(AssertUnwindSafe(|| f(self))) {
            Ok(Ok(status)) => status,
            Ok(Err(MujocoError::Diverged(d))) => {
                self.divergence = serde_json::to_string(&d)
                    .ok()
                    .and_then(|json| CString::new(json).ok());
                self.fail(d.to_string())
            }
            Ok(Err(e)) => self.fail(e.to_string()),
            Err(_) => self.fail("internal error (panic) in the touchdown MuJoCo library".into()),
        }
    }

    fn advance(&mut self) -> Result<i32, MujocoError> {
        let (Some(landing), Some(p)) = (self.landing.as_mut(), self.pointers) else {
            return Err(MujocoError::Binding(
                "advance before a successful bind".into(),
            ));
        };
        let s = landing.sizes();
        let n = |x: i32| x as usize;
        let mut warnings = [0i32; MUJOCO_WARNINGS.len()];
        // SAFETY: the runner passed MuJoCo's arrays of the model whose sizes it gave to bind
        // (checked there against the scenario); they live as long as its MjModel/MjData, and
        // nothing else touches them during this call (MuJoCo is between mj_step1 and mj_step2).
        let mut arrays = unsafe {
            for (k, w) in warnings.iter_mut().enumerate() {
                *w = *p.warning_number.add(k * n(p.warning_stride));
            }
            MjArrays {
                qpos: std::slice::from_raw_parts(p.qpos, n(s.nq)),
                qvel: std::slice::from_raw_parts(p.qvel, n(s.nv)),
                ten_length: std::slice::from_raw_parts(p.ten_length, n(s.ntendon)),
                ten_velocity: std::slice::from_raw_parts(p.ten_velocity, n(s.ntendon)),
                site_xpos: std::slice::from_raw_parts(p.site_xpos, 3 * n(s.nsite)),
                xpos: std::slice::from_raw_parts(p.xpos, 3 * n(s.nbody)),
                sensordata: std::slice::from_raw_parts(p.sensordata, n(s.nsensordata)),
                energy: std::slice::from_raw_parts(p.energy, 2),
                warnings: &warnings,
                ctrl: std::slice::from_raw_parts_mut(p.ctrl, n(s.nu)),
                friction_bound: std::slice::from_raw_parts_mut(p.friction_bound, landing.legs()),
                qfrc_applied: std::slice::from_raw_parts_mut(p.qfrc_applied, n(s.nv)),
                xfrc_applied: std::slice::from_raw_parts_mut(p.xfrc_applied, 6 * n(s.nbody)),
            }
        };
        Ok(i32::from(landing.advance(&mut arrays)?))
    }

    /// The landing's steps, each `mj_step1`, [`Runner::advance`], the stroke joints'
    /// dry-friction bounds copied into their friction rows, `mj_step2`, until `advance` ends
    /// the run (returns its status: 1) or fails.
    ///
    /// # Safety
    /// `mj` holds MuJoCo's half-steps and the model and data this runner was bound to, alive
    /// for the call, and nothing else touches them meanwhile.
    unsafe fn run(&mut self, mj: &MjLoop) -> Result<i32, MujocoError> {
        let binding = |m: &str| Err(MujocoError::Binding(m.into()));
        let (Some(step1), Some(step2), Some(set_log_handler)) =
            (mj.step1, mj.step2, mj.set_log_handler)
        else {
            return binding("null mj_step1, mj_step2 or mju_setLogHandler");
        };
        let (Some(landing), Some(p)) = (self.landing.as_ref(), self.pointers) else {
            return binding("run before a successful bind");
        };
        if mj.model.is_null()
            || mj.data.is_null()
            || mj.frictionloss.is_null()
            || mj.divergence_path.is_null()
        {
            return binding("null model, data, friction rows or diagnostic path");
        }
        let legs = landing.legs();
        let rows = (mj.data as *const u8).add(EFC_FRICTIONLOSS_OFFSET) as *const *mut f64;
        if !std::ptr::eq(*rows, mj.frictionloss) {
            return Err(MujocoError::Binding(format!(
                "mjData.efc_frictionloss is not at byte {EFC_FRICTIONLOSS_OFFSET} of this MuJoCo's \
                 mjData: the library is built for the MuJoCo pinned in python/requirements.txt \
                 (run scripts/setup-python)"
            )));
        }
        let handler = LogHandlerSet {
            set: set_log_handler,
            previous: set_log_handler(Some(on_mujoco_message)),
        };
        // The sink's landing is taken anew before each half-step, after `advance` has
        // borrowed the landing mutably: the handler only reads it, and only while MuJoCo runs.
        let sink = |r: &Runner| {
            ERROR_SINK.with(|s| {
                s.set(Some(ErrorSink {
                    landing: r
                        .landing
                        .as_ref()
                        .map_or(std::ptr::null(), |l| l as *const _),
                    path: mj.divergence_path,
                    previous: handler.previous,
                }))
            })
        };
        loop {
            sink(self);
            step1(mj.model, mj.data);
            let status = self.advance()?;
            if status != 0 {
                return Ok(status);
            }
            let row = (*rows).add(mj.first_row);
            for k in 0..legs {
                *row.add(k) = *p.friction_bound.add(k);
            }
            sink(self);
            step2(mj.model, mj.data);
        }
    }
}

/// A string argument, or an error naming it.
///
/// # Safety
/// `s` is null or a NUL-terminated string.
unsafe fn text<'a>(s: *const c_char, what: &str) -> Result<&'a str, MujocoError> {
    if s.is_null() {
        return Err(MujocoError::Binding(format!("{what} is null")));
    }
    CStr::from_ptr(s)
        .to_str()
        .map_err(|_| MujocoError::Binding(format!("{what} is not UTF-8")))
}

/// Loads the scenario file `scenario` (with the MuJoCo time step `timestep`, s, if it is
/// positive) and exports its model. Always returns a runner (free it with
/// [`touchdown_mujoco_close`]); on failure its error is set and it has no model.
///
/// # Safety
/// `scenario` is null or a NUL-terminated path.
#[no_mangle]
pub unsafe extern "C" fn touchdown_mujoco_open(
    scenario: *const c_char,
    timestep: f64,
) -> *mut Runner {
    let mut runner = Runner {
        scenario: None,
        xml: None,
        landing: None,
        pointers: None,
        error: None,
        divergence: None,
    };
    runner.guard(|r| {
        let path = text(scenario, "scenario path")?;
        let mut sc = Scenario::load(Path::new(path))?;
        sc.require_engine(Engine::Mujoco, crate::unsupported)?;
        if timestep > 0.0 {
            let seconds = sc.units().time();
            sc = sc.with_mujoco(|m| m.timestep = Some(timestep / seconds))?;
        }
        r.xml = Some(
            CString::new(crate::export(&sc)?)
                .map_err(|_| MujocoError::Binding("model text contains NUL".into()))?,
        );
        r.scenario = Some(sc);
        Ok(0)
    });
    Box::into_raw(Box::new(runner))
}

/// The divergence that stopped the landing in the runner's last call, as JSON
/// (`touchdown_record::Divergence`), or null if it did not stop one. Valid until the next call
/// on this runner.
///
/// # Safety
/// `runner` comes from [`touchdown_mujoco_open`] and was not closed.
#[no_mangle]
pub unsafe extern "C" fn touchdown_mujoco_divergence(runner: *const Runner) -> *const c_char {
    match runner.as_ref().and_then(|r| r.divergence.as_ref()) {
        Some(d) => d.as_ptr(),
        None => std::ptr::null(),
    }
}

/// The runner's last error message, or null if the last call succeeded. Valid until the next
/// call on this runner.
///
/// # Safety
/// `runner` comes from [`touchdown_mujoco_open`] and was not closed.
#[no_mangle]
pub unsafe extern "C" fn touchdown_mujoco_error(runner: *const Runner) -> *const c_char {
    match runner.as_ref().and_then(|r| r.error.as_ref()) {
        Some(e) => e.as_ptr(),
        None => std::ptr::null(),
    }
}

/// The MJCF model of the scenario (`mjcf::export`), or null if opening failed. Valid until the
/// runner is closed.
///
/// # Safety
/// `runner` comes from [`touchdown_mujoco_open`] and was not closed.
#[no_mangle]
pub unsafe extern "C" fn touchdown_mujoco_model_xml(runner: *const Runner) -> *const c_char {
    match runner.as_ref().and_then(|r| r.xml.as_ref()) {
        Some(x) => x.as_ptr(),
        None => std::ptr::null(),
    }
}

/// Binds the landing to MuJoCo's arrays: `legs` gear indices at `index`, the model's `sizes`,
/// the array `pointers`, MuJoCo's version (for the summary) and, unless null, the path of the
/// history file to write (`history.csv`). Returns 0, or −1 with the error set.
///
/// # Safety
/// `runner` comes from [`touchdown_mujoco_open`]; `index` points to `legs` entries; `sizes` and
/// `pointers` are valid and describe the model loaded from [`touchdown_mujoco_model_xml`];
/// strings are NUL-terminated.
#[no_mangle]
pub unsafe extern "C" fn touchdown_mujoco_bind(
    runner: *mut Runner,
    index: *const GearIndex,
    legs: usize,
    sizes: *const ModelSizes,
    pointers: *const MjPointers,
    mujoco_version: *const c_char,
    history: *const c_char,
) -> i32 {
    let Some(runner) = runner.as_mut() else {
        return -1;
    };
    runner.guard(|r| {
        let sc = r
            .scenario
            .as_ref()
            .ok_or_else(|| MujocoError::Binding("bind after a failed open".into()))?;
        if index.is_null() || sizes.is_null() || pointers.is_null() {
            return Err(MujocoError::Binding("null index, sizes or pointers".into()));
        }
        let p = *pointers;
        let fields = [
            p.qpos,
            p.qvel,
            p.ten_length,
            p.ten_velocity,
            p.site_xpos,
            p.xpos,
            p.sensordata,
            p.energy,
            p.ctrl,
            p.friction_bound,
        ];
        if fields.iter().any(|f| f.is_null()) || p.warning_number.is_null() {
            return Err(MujocoError::Binding(
                "a MuJoCo array pointer is null".into(),
            ));
        }
        if p.warning_stride < 1 {
            return Err(MujocoError::Binding(format!(
                "warning stride {} (expected ≥ 1)",
                p.warning_stride
            )));
        }
        let version = text(mujoco_version, "MuJoCo version")?;
        let history = if history.is_null() {
            None
        } else {
            let path = text(history, "history path")?;
            Some(History::create(Path::new(path), sc.legs.len())?)
        };
        let index = std::slice::from_raw_parts(index, legs).to_vec();
        r.landing = Some(MujocoLanding::new(sc, index, *sizes, version, history)?);
        r.pointers = Some(p);
        Ok(0)
    })
}

/// One step's work between `mj_step1` and `mj_step2` ([`MujocoLanding::advance`]): 0 to go
/// on stepping, 1 when the run has ended (no forces written), −1 on an error or a divergence
/// (the message says when, where and which law).
///
/// # Safety
/// `runner` comes from [`touchdown_mujoco_open`] and was bound; MuJoCo's arrays are alive.
#[no_mangle]
pub unsafe extern "C" fn touchdown_mujoco_advance(runner: *mut Runner) -> i32 {
    match runner.as_mut() {
        Some(r) => r.guard(Runner::advance),
        None => -1,
    }
}

/// Stops the landing on an error MuJoCo raised in a step of a loop Python keeps (`what`: the
/// `mujoco.FatalError`'s words): sets the runner's divergence
/// ([`MujocoLanding::engine_error`], read with [`touchdown_mujoco_divergence`]) and error, and
/// returns −1.
///
/// # Safety
/// `runner` comes from [`touchdown_mujoco_open`] and was bound; `what` is a NUL-terminated
/// string.
#[no_mangle]
pub unsafe extern "C" fn touchdown_mujoco_engine_error(
    runner: *mut Runner,
    what: *const c_char,
) -> i32 {
    match runner.as_mut() {
        Some(r) => r.guard(|r| {
            let what = text(what, "MuJoCo's error")?;
            let landing = r
                .landing
                .as_ref()
                .ok_or_else(|| MujocoError::Binding("an error before a successful bind".into()))?;
            Err(MujocoError::Diverged(Box::new(landing.engine_error(what))))
        }),
        None => -1,
    }
}

/// A clock that reads 0 s, for MuJoCo's profiling callback (`mjcb_time`): the runner reads
/// none of MuJoCo's timers (`mjData.timer`), whose clock costs about 4 % of a landing (two
/// reads around each of about fifteen stages a step). Only the runner's process uses MuJoCo.
#[no_mangle]
pub extern "C" fn touchdown_mujoco_no_clock() -> f64 {
    0.0
}

/// The landing's whole loop ([`Runner::run`]): MuJoCo's `mj_step1`, the step's work of
/// [`touchdown_mujoco_advance`], the stroke joints' dry-friction bounds written into their
/// friction rows, `mj_step2`, until the run ends. Returns 1 when it has ended, −1 on an error
/// or a divergence (the message says when, where and which law).
///
/// # Safety
/// `runner` comes from [`touchdown_mujoco_open`] and was bound; `mj` points to an [`MjLoop`]
/// whose functions are MuJoCo's `mj_step1` and `mj_step2` and whose model and data are those
/// bound, alive for the call.
#[no_mangle]
pub unsafe extern "C" fn touchdown_mujoco_run(runner: *mut Runner, mj: *const MjLoop) -> i32 {
    let (Some(runner), Some(mj)) = (runner.as_mut(), mj.as_ref()) else {
        return -1;
    };
    runner.guard(|r| unsafe { r.run(mj) })
}

/// Ends the run: flushes the history and writes the summary (`summary.json`) to `summary`.
/// Returns 0, or −1 with the error set.
///
/// # Safety
/// `runner` comes from [`touchdown_mujoco_open`] and was bound; `summary` is a NUL-terminated
/// path.
#[no_mangle]
pub unsafe extern "C" fn touchdown_mujoco_finish(
    runner: *mut Runner,
    summary: *const c_char,
) -> i32 {
    let Some(runner) = runner.as_mut() else {
        return -1;
    };
    runner.guard(|r| {
        let path = text(summary, "summary path")?;
        let landing = r
            .landing
            .as_mut()
            .ok_or_else(|| MujocoError::Binding("finish before a successful bind".into()))?;
        landing.finish_history()?;
        std::fs::write(path, landing.summary().to_json())
            .map_err(|e| std::io::Error::new(e.kind(), format!("cannot write {path}: {e}")))?;
        Ok(0)
    })
}

/// Frees a runner.
///
/// # Safety
/// `runner` comes from [`touchdown_mujoco_open`] and is not used afterwards.
#[no_mangle]
pub unsafe extern "C" fn touchdown_mujoco_close(runner: *mut Runner) {
    if !runner.is_null() {
        drop(Box::from_raw(runner));
    }
}
