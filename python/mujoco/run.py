"""Runs a Touchdown scenario on MuJoCo, driven by the shared Rust force laws.

Usage:
  run.py SCENARIO --out DIR --library LIB [--timestep S] [--history] [--profile] [--viewer]
  run.py --serve --library LIB

The Rust library LIB (crate touchdown-mujoco, built by cargo as
target/<profile>/deps/libtouchdown_mujoco.so) loads the scenario, generates the MJCF model
(the same as `touchdown export-mjcf`), and owns everything but MuJoCo itself: the strut laws,
hysteresis, energy ledger, stability criteria, summary.json and history.csv. This script loads the
model with the pinned `mujoco` package and hands LIB the model, its data and MuJoCo's own
mj_step1 and mj_step2, and LIB steps it (touchdown_mujoco_run), each step:

    mj_step1   positions, velocities, tendons and sensors of the state, and the
               constraint rows
    advance    (Rust) book the last step, commit the honeycombs, evaluate the laws, write
               ctrl, the stroke joints' dry-friction bounds (bearing friction),
               and the engine and RCS loads on the vehicle (qfrc_applied),
               the curbs' and obstacle walls' force on the footpads (xfrc_applied)
    (rows)     copy the dry-friction bounds into the stroke joints' friction rows
               (efc_frictionloss), which mj_step1 built from the model's placeholder
    mj_step2   forces, constraints, integration

The viewer's and the profiler's loops are the same steps written here in Python.

Options:
  --history   also write DIR/history.csv (one row per step)
  --profile   step in a Python loop with a clock around each call and print a JSON line with
              the wall time spent in MuJoCo (with its binding calls), in the Rust library and
              in the loop itself, per landing and per step (what the library's loop saves)
  --viewer    watch the law-driven run in MuJoCo's passive viewer (needs a display and the
              `glfw` package, which the full `mujoco` package brings; see docs/engines.md)

With --serve the runner lands one scenario per line of standard input, a JSON object
{"scenario": PATH, "out": DIR, "history": BOOL}, and answers each with one line
`touchdown-reply {"status": S, "message": "..."}` on standard output (S as the exit status
below; the files as below, in DIR), until standard input closes: Python's and MuJoCo's start-up
are paid once for many landings (a campaign's). A MuJoCo error in a step (mju_error, which never
returns) ends the runner instead, with status 4 and the landing's diagnostic in its DIR.

Exit status: 0 done; 1 the run failed (the message on stderr); 2 bad arguments or library; 3
`mujoco` is not installed in this interpreter; 4 the landing stopped with a diagnostic (when,
where and which law: the message on stderr, and the diagnostic as data in DIR/divergence.json,
read back by the `touchdown` command).
"""

import argparse
import ctypes
import functools
import glob
import json
import os
import sys
import time

SETUP_STATUS = 3
STOPPED_STATUS = 4
DIVERGENCE_FILE = "divergence.json"


REPLY = "touchdown-reply "


class Failure(Exception):
    """A landing that did not complete: its message and the exit status that says why."""

    def __init__(self, message, status=1):
        super().__init__(message)
        self.message = message
        self.status = status


def fail(message, status=1):
    raise Failure(message, status)


try:
    import mujoco
    import numpy
except ImportError as e:
    print(
        f"run.py: the pinned MuJoCo (python/requirements.txt) cannot be imported by {sys.executable}: {e}; "
        "run scripts/setup-python",
        file=sys.stderr,
    )
    sys.exit(SETUP_STATUS)

MUJOCO_LOG = "MUJOCO_LOG.TXT"


def refuse_warnings(log, when):
    """Fails if MuJoCo logged a warning (a setting it silently replaced, for one): a result
    computed with settings the user did not ask for is not a result."""
    if os.path.exists(log):
        with open(log, encoding="utf-8", errors="replace") as f:
            lines = [line.strip() for line in f if line.strip()]
        os.remove(log)
        fail(f"MuJoCo warned while {when}: {' / '.join(lines[-3:])}")


LEG_FIELDS = 15  # GearIndex: 15 int32 per leg (crates/mujoco/src/landing.rs)


class MjPointers(ctypes.Structure):
    """Mirror of touchdown_mujoco::ffi::MjPointers."""

    _fields_ = [
        ("qpos", ctypes.c_void_p),
        ("qvel", ctypes.c_void_p),
        ("ten_length", ctypes.c_void_p),
        ("ten_velocity", ctypes.c_void_p),
        ("site_xpos", ctypes.c_void_p),
        ("xpos", ctypes.c_void_p),
        ("sensordata", ctypes.c_void_p),
        ("energy", ctypes.c_void_p),
        ("warning_number", ctypes.c_void_p),
        ("warning_stride", ctypes.c_int32),
        ("ctrl", ctypes.c_void_p),
        ("friction_bound", ctypes.c_void_p),
        ("qfrc_applied", ctypes.c_void_p),
        ("xfrc_applied", ctypes.c_void_p),
    ]


class MjLoop(ctypes.Structure):
    """Mirror of touchdown_mujoco::ffi::MjLoop."""

    _fields_ = [
        ("step1", ctypes.c_void_p),
        ("step2", ctypes.c_void_p),
        ("model", ctypes.c_void_p),
        ("data", ctypes.c_void_p),
        ("frictionloss", ctypes.c_void_p),
        ("first_row", ctypes.c_size_t),
        ("set_log_handler", ctypes.c_void_p),
        ("divergence_path", ctypes.c_char_p),
    ]


@functools.cache
def half_steps():
    """The addresses of mj_step1, mj_step2 and mju_setLogHandler in the MuJoCo library the
    `mujoco` package loaded (opening the same file again gives the same library)."""
    folder = os.path.dirname(mujoco.__file__)
    found = sorted(glob.glob(os.path.join(folder, "libmujoco.so*")))
    if not found:
        fail(f"no MuJoCo library (libmujoco.so*) in {folder}: run scripts/setup-python", SETUP_STATUS)
    lib = ctypes.CDLL(found[0])
    return tuple(
        ctypes.cast(getattr(lib, f), ctypes.c_void_p).value
        for f in ("mj_step1", "mj_step2", "mju_setLogHandler")
    )


class ModelSizes(ctypes.Structure):
    """Mirror of touchdown_mujoco::landing::ModelSizes."""

    _fields_ = [
        (name, ctypes.c_int32)
        for name in ("nq", "nv", "nu", "ntendon", "nsite", "nbody", "nsensordata")
    ]


def load_library(path):
    try:
        lib = ctypes.CDLL(path)
    except OSError as e:
        fail(f"cannot load the touchdown MuJoCo library {path}: {e}", 2)
    p = ctypes.c_void_p
    lib.touchdown_mujoco_open.argtypes = [ctypes.c_char_p, ctypes.c_double]
    lib.touchdown_mujoco_open.restype = p
    lib.touchdown_mujoco_error.argtypes = [p]
    lib.touchdown_mujoco_error.restype = ctypes.c_char_p
    lib.touchdown_mujoco_divergence.argtypes = [p]
    lib.touchdown_mujoco_divergence.restype = ctypes.c_char_p
    lib.touchdown_mujoco_model_xml.argtypes = [p]
    lib.touchdown_mujoco_model_xml.restype = ctypes.c_char_p
    lib.touchdown_mujoco_bind.argtypes = [
        p,
        ctypes.POINTER(ctypes.c_int32),
        ctypes.c_size_t,
        ctypes.POINTER(ModelSizes),
        ctypes.POINTER(MjPointers),
        ctypes.c_char_p,
        ctypes.c_char_p,
    ]
    lib.touchdown_mujoco_bind.restype = ctypes.c_int32
    lib.touchdown_mujoco_advance.argtypes = [p]
    lib.touchdown_mujoco_advance.restype = ctypes.c_int32
    lib.touchdown_mujoco_run.argtypes = [p, ctypes.POINTER(MjLoop)]
    lib.touchdown_mujoco_run.restype = ctypes.c_int32
    lib.touchdown_mujoco_engine_error.argtypes = [p, ctypes.c_char_p]
    lib.touchdown_mujoco_engine_error.restype = ctypes.c_int32
    lib.touchdown_mujoco_no_clock.argtypes = []
    lib.touchdown_mujoco_no_clock.restype = ctypes.c_double
    lib.touchdown_mujoco_finish.argtypes = [p, ctypes.c_char_p]
    lib.touchdown_mujoco_finish.restype = ctypes.c_int32
    lib.touchdown_mujoco_close.argtypes = [p]
    lib.touchdown_mujoco_close.restype = None
    return lib


def gear_index(model, legs):
    """Per leg, the GearIndex entries located by the export's element names."""

    def ident(kind, name):
        i = mujoco.mj_name2id(model, kind, name)
        if i < 0:
            fail(f"the model has no {kind.name[6:].lower()} named {name!r}", 2)
        return i

    obj = mujoco.mjtObj
    table = []
    for n in range(1, legs + 1):
        stroke = ident(obj.mjOBJ_JOINT, f"leg{n}_stroke")
        sensor = [
            int(model.sensor_adr[ident(obj.mjOBJ_SENSOR, f"leg{n}_{s}")])
            for s in ("contact", "pad_velocity", "pad_rate")
        ]
        table += [
            int(model.jnt_qposadr[stroke]),
            int(model.jnt_dofadr[stroke]),
            ident(obj.mjOBJ_TENDON, f"leg{n}_s31"),
            ident(obj.mjOBJ_TENDON, f"leg{n}_s41"),
            ident(obj.mjOBJ_ACTUATOR, f"leg{n}_primary"),
            ident(obj.mjOBJ_ACTUATOR, f"leg{n}_s31"),
            ident(obj.mjOBJ_ACTUATOR, f"leg{n}_s41"),
            ident(obj.mjOBJ_SITE, f"leg{n}_b3"),
            ident(obj.mjOBJ_SITE, f"leg{n}_b4"),
            ident(obj.mjOBJ_SITE, f"leg{n}_point1"),
            ident(obj.mjOBJ_BODY, f"leg{n}_outer"),
            ident(obj.mjOBJ_BODY, f"leg{n}_footpad"),
            *sensor,
        ]
    assert len(table) == LEG_FIELDS * legs
    return (ctypes.c_int32 * len(table))(*table)


def pointer(array, dtype):
    """The address of a MuJoCo array (a view into MuJoCo's own memory, never a copy)."""
    if array.dtype != dtype or not array.flags["C_CONTIGUOUS"]:
        fail(f"unexpected MuJoCo array layout {array.dtype} {array.strides}", 2)
    return array.ctypes.data


def friction_rows(model, data, index, legs):
    """The rows of MuJoCo's constraints that hold the stroke joints' dry friction, in gear order.

    mj_step1 builds a joint's friction row only where the model's dof_frictionloss is not zero
    (the export gives the stroke joints a placeholder, and no other joint or tendon any), after
    the equality constraints (the export has none) and before the limits and contacts: the
    same rows every step. The runner writes each step's bounds into them before mj_step2; the
    export turns constraint islands off, so that the solver reads these rows and not copies."""
    mujoco.mj_step1(model, data)
    dofs = [index[LEG_FIELDS * n + 1] for n in range(legs)]
    first = int(data.ne)
    rows = slice(first, first + legs)
    kind = mujoco.mjtConstraint.mjCNSTR_FRICTION_DOF
    if (
        int(data.nf) != legs
        or list(data.efc_type[rows]) != [kind] * legs
        or list(data.efc_id[rows]) != dofs
    ):
        fail(
            f"the model's friction rows are not the stroke joints' (nf {int(data.nf)}, "
            f"ids {list(data.efc_id[rows])}, expected {dofs}): was it exported by this version?",
            2,
        )
    return rows


def land(lib, scenario, out, timestep=0.0, history=False, mode="plain"):
    """Lands `scenario` (an absolute path) and writes summary.json (and with `history`
    history.csv) into `out`; `mode` is plain, profile or viewer. Returns the timing of a
    profiled run, else None; raises Failure when the landing does not complete."""
    # MuJoCo writes its warnings to MUJOCO_LOG.TXT in the current directory: run in the output
    # directory, so that no log is left where the user stands and the warnings are read below.
    os.makedirs(out, exist_ok=True)
    os.chdir(out)
    log = os.path.join(out, MUJOCO_LOG)
    if os.path.exists(log):
        os.remove(log)
    h = lib.touchdown_mujoco_open(scenario.encode(), timestep)

    def check(status):
        if status < 0:
            message = lib.touchdown_mujoco_error(h)
            message = message.decode() if message else "unknown error"
            divergence = lib.touchdown_mujoco_divergence(h)
            if divergence:
                with open(os.path.join(out, DIVERGENCE_FILE), "wb") as f:
                    f.write(divergence)
                fail(message, STOPPED_STATUS)
            fail(message)
        return status

    try:
        xml = lib.touchdown_mujoco_model_xml(h)
        if not xml:
            check(-1)
        try:
            model = mujoco.MjModel.from_xml_string(xml.decode())
        except ValueError as e:
            fail(f"MuJoCo cannot compile the scenario's model: {e}")
        refuse_warnings(log, "compiling the scenario's model")
        data = mujoco.MjData(model)
        key = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "touchdown")
        mujoco.mj_resetDataKeyframe(model, data, key)
        legs = int(model.nu) // 3
        index = gear_index(model, legs)
        sizes = ModelSizes(
            model.nq, model.nv, model.nu, model.ntendon, model.nsite, model.nbody, model.nsensordata
        )
        f64 = data.qpos.dtype
        rows = friction_rows(model, data, index, legs)
        bounds = numpy.zeros(legs)
        warnings = data.warning.number
        ptrs = MjPointers(
            pointer(data.qpos, f64),
            pointer(data.qvel, f64),
            pointer(data.ten_length, f64),
            pointer(data.ten_velocity, f64),
            pointer(data.site_xpos, f64),
            pointer(data.xpos, f64),
            pointer(data.sensordata, f64),
            pointer(data.energy, f64),
            warnings.ctypes.data,
            warnings.strides[0] // warnings.itemsize,
            pointer(data.ctrl, f64),
            pointer(bounds, f64),
            pointer(data.qfrc_applied, f64),
            pointer(data.xfrc_applied, f64),
        )
        history = os.path.join(out, "history.csv").encode() if history else None
        check(
            lib.touchdown_mujoco_bind(
                h, index, legs, ctypes.byref(sizes), ctypes.byref(ptrs),
                mujoco.__version__.encode(), history,
            )
        )
        timing = None
        friction = (rows, bounds)
        if mode == "viewer":
            status = run_with_viewer(lib, h, model, data, friction)
        elif mode == "profile":
            status, timing = run_profiled(lib, h, model, data, friction)
        else:
            status = run(lib, h, model, data, friction, out)
        check(status)
        refuse_warnings(log, "running the landing")
        check(lib.touchdown_mujoco_finish(h, os.path.join(out, "summary.json").encode()))
    finally:
        lib.touchdown_mujoco_close(h)
    return timing


def serve(lib):
    """Lands the scenarios asked for on standard input, one reply line each (see the module
    documentation), until standard input closes."""
    for line in sys.stdin:
        if not line.strip():
            continue
        try:
            request = json.loads(line)
            land(
                lib,
                os.path.abspath(request["scenario"]),
                os.path.abspath(request["out"]),
                history=bool(request.get("history", False)),
            )
            reply = {"status": 0, "message": ""}
        except Failure as e:
            reply = {"status": e.status, "message": e.message}
        except Exception as e:  # noqa: BLE001 - the caller gets the project's message
            reply = {"status": 1, "message": f"unexpected {type(e).__name__} in the MuJoCo runner: {e}"}
        sys.stdout.write(REPLY + json.dumps(reply) + "\n")
        sys.stdout.flush()


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scenario", nargs="?")
    ap.add_argument("--out")
    ap.add_argument("--library", required=True)
    ap.add_argument("--timestep", type=float, default=0.0)
    ap.add_argument("--history", action="store_true")
    ap.add_argument("--profile", action="store_true")
    ap.add_argument("--viewer", action="store_true")
    ap.add_argument("--serve", action="store_true")
    args = ap.parse_args(argv)
    lib = load_library(os.path.abspath(args.library))
    if args.serve:
        serve(lib)
        return
    if not args.scenario or not args.out:
        fail("SCENARIO and --out are required (or --serve)", 2)
    mode = "viewer" if args.viewer else "profile" if args.profile else "plain"
    timing = land(
        lib,
        os.path.abspath(args.scenario),
        os.path.abspath(args.out),
        args.timestep,
        args.history,
        mode,
    )
    if timing is not None:
        print(json.dumps(timing))





def run(lib, h, model, data, friction, out):
    """The plain loop, in the library (touchdown_mujoco_run): no Python per step. `friction`:
    the stroke joints' friction rows (after an mj_step1) and the bounds advance writes for
    them. A MuJoCo error in a step ends this process from the library, with the landing's
    diagnostic in `out` (exit status 4)."""
    rows, _ = friction
    # MuJoCo's profiling timers, which nothing reads, cost a clock read at each stage's ends.
    mujoco.set_mjcb_time(lib.touchdown_mujoco_no_clock)
    step1, step2, set_log_handler = half_steps()
    mj = MjLoop(
        step1, step2, model._address, data._address, data.efc_frictionloss.ctypes.data, rows.start,
        set_log_handler, os.path.join(out, DIVERGENCE_FILE).encode(),
    )
    return lib.touchdown_mujoco_run(h, ctypes.byref(mj))


def engine_error(lib, h, error):
    """The status of a landing whose step MuJoCo stopped with `error` (a mujoco.FatalError) in
    a loop Python keeps: the library records the diagnostic."""
    return lib.touchdown_mujoco_engine_error(h, str(error).encode())


def run_profiled(lib, h, model, data, friction):
    """The loop with a clock around each call; the clock's own cost is measured and removed."""
    clock = time.perf_counter_ns
    step1, step2, advance = mujoco.mj_step1, mujoco.mj_step2, lib.touchdown_mujoco_advance
    rows, bounds = friction
    reads = 100000
    t0 = clock()
    for _ in range(reads):
        clock()
    per_read = (clock() - t0) / reads
    t_mujoco = t_rust = 0
    steps = 0
    start = clock()
    while True:
        try:
            a = clock()
            step1(model, data)
            b = clock()
            status = advance(h)
            c = clock()
            t_mujoco += b - a
            t_rust += c - b
            if status != 0:
                break
            data.efc_frictionloss[rows] = bounds
            a = clock()
            step2(model, data)
            t_mujoco += clock() - a
        except mujoco.FatalError as e:
            status = engine_error(lib, h, e)
            break
        steps += 1
    total = clock() - start
    # Per step: 5 clock reads, of which about one is inside each of the 3 timed spans.
    calls = steps + 1
    t_mujoco -= per_read * (2 * calls)
    t_rust -= per_read * calls
    clocks = per_read * 5 * calls
    python = total - t_mujoco - t_rust - clocks
    return status, {
        "steps": steps,
        "loop_s": (total - clocks) * 1e-9,
        "mujoco_s": t_mujoco * 1e-9,
        "rust_s": t_rust * 1e-9,
        "python_s": python * 1e-9,
        "per_step_us": {
            "total": (total - clocks) * 1e-3 / max(steps, 1),
            "mujoco": t_mujoco * 1e-3 / max(steps, 1),
            "rust": t_rust * 1e-3 / max(steps, 1),
            "python": python * 1e-3 / max(steps, 1),
        },
    }


def run_with_viewer(lib, h, model, data, friction):
    """The loop with MuJoCo's passive viewer, slowed so that 1 s of landing takes 20 s."""
    try:
        import mujoco.viewer
    except ImportError as e:
        fail(
            f"the viewer needs the full `mujoco` package or `glfw` in {sys.executable} ({e}); "
            "see docs/engines.md, 'Watching the law-driven run'",
            2,
        )
    rows, bounds = friction
    slow = 20.0
    frame = 1.0 / 60.0
    with mujoco.viewer.launch_passive(model, data) as viewer:
        wall = time.perf_counter()
        while viewer.is_running():
            try:
                mujoco.mj_step1(model, data)
                status = lib.touchdown_mujoco_advance(h)
                if status != 0:
                    break
                data.efc_frictionloss[rows] = bounds
                mujoco.mj_step2(model, data)
            except mujoco.FatalError as e:
                status = engine_error(lib, h, e)
                break
            if data.time * slow >= time.perf_counter() - wall + frame:
                viewer.sync()
                time.sleep(frame)
        else:
            status = 1
        while viewer.is_running():
            viewer.sync()
            time.sleep(frame)
    return status


if __name__ == "__main__":
    try:
        main(sys.argv[1:])
    except Failure as e:
        print(f"run.py: {e.message}", file=sys.stderr)
        sys.exit(e.status)
    except Exception as e:  # noqa: BLE001 - the caller gets the project's message, never a traceback
        print(f"run.py: unexpected {type(e).__name__} in the MuJoCo runner: {e}", file=sys.stderr)
        sys.exit(1)
