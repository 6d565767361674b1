"""The Python package `touchdown` (python/touchdown, crates/python), run by scripts/test."""

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import touchdown
from touchdown import campaign

ROOT = Path(__file__).resolve().parents[2]
SCENARIO = ROOT / "scenarios" / "table-i-2-2-vv8.toml"
TOUCHDOWN = ROOT / "target" / "debug" / "touchdown"


def test_a_landing_returns_its_summary_and_history_as_arrays():
    landing = touchdown.run(SCENARIO)
    summary, history = landing["summary"], landing["history"]
    assert summary["engine"] == "core" and summary["outcome"] in ("stable", "unstable", "undecided")
    assert len(summary["max_primary_stroke_m"]) == 4
    assert isinstance(history["t_s"], np.ndarray) and history["t_s"][0] == 0.0
    assert len(history["t_s"]) == summary["steps"] + 1
    # The history's largest primary stroke is the summary's.
    assert np.isclose(history["leg1_primary_stroke_m"].max(), summary["max_primary_stroke_m"][0], rtol=1e-8)


def test_a_strut_past_its_capacity_is_named_in_the_summary_and_the_history():
    # The stroke-out drop bottoms its four primaries on their end stops; every strut of the
    # Table I landing stays within its capacity.
    landing = touchdown.run(ROOT / "scenarios" / "stroke-out.toml")
    summary, history = landing["summary"], landing["history"]
    past = summary["past_capacity"]
    assert [p["strut"] for p in past] == [f"leg{i}.primary" for i in range(1, 5)]
    capacity = summary["strut_capacity"]["primary"]
    for p in past:
        assert p["capacity_m"] == capacity["stroke_m"] and p["stroke_of_capacity"] > 1.0
        assert np.isclose(p["peak_stop_force_n"], capacity["stop_rate_n_m"] * p["past_capacity_m"], rtol=1e-12)
    # The history's stop force peaks at the summary's, and is zero within the capacity.
    stop = history["leg1_primary_stop_force_n"]
    assert np.isclose(stop.max(), past[0]["peak_stop_force_n"], rtol=1e-6)
    within = history["leg1_primary_stroke_m"] <= capacity["stroke_m"]
    assert within.any() and (stop[within] == 0.0).all()
    assert touchdown.run(SCENARIO, history=False)["summary"]["past_capacity"] == []


def test_the_summary_is_the_command_lines():
    cli = subprocess.run([TOUCHDOWN, "run", SCENARIO, "--format", "json"], capture_output=True, check=True)
    import json

    assert touchdown.run(SCENARIO, history=False)["summary"] == json.loads(cli.stdout)


def test_a_settled_landing_ends_early_with_the_full_runs_maxima():
    vv10 = ROOT / "scenarios" / "table-i-2-2-vv10.toml"
    full = touchdown.run(vv10, history=False)["summary"]
    early = touchdown.run(vv10, overrides={"stability.settled_tolerance": 0.001}, history=False)["summary"]
    assert "settled_time_s" not in full
    assert early["t_end_s"] == early["settled_time_s"] < full["t_end_s"]
    assert early["outcome"] == full["outcome"]
    eps = 0.001 * 0.3048  # the vehicle file's length unit is the foot
    assert np.allclose(early["max_primary_stroke_m"], full["max_primary_stroke_m"], rtol=0, atol=eps)
    assert early["peak_primary_force_n"] == full["peak_primary_force_n"]
    assert early["peak_pitch_rate_rad_s"] == full["peak_pitch_rate_rad_s"]
    for extreme in ("min_pitch_rate_rad_s", "max_pitch_rate_rad_s"):
        assert early[extreme] == full[extreme]
    with pytest.raises(touchdown.ScenarioInvalid) as e:
        touchdown.run(ROOT / "scenarios" / "soil-drop.toml", overrides={"stability.settled_tolerance": 0.001})
    assert "stability.settled_tolerance" in str(e.value) and "soil" in str(e.value)


def test_overrides_and_text_change_the_landing():
    base = touchdown.run(SCENARIO, history=False)["summary"]
    faster = touchdown.run(SCENARIO, overrides={"touchdown.vertical_velocity": -10.0}, history=False)["summary"]
    assert faster["max_primary_stroke_m"][0] > base["max_primary_stroke_m"][0]
    flat = (ROOT / "scenarios" / "flat-drop.toml").read_text()
    assert "extends" in flat
    with pytest.raises(touchdown.ScenarioInvalid) as e:
        touchdown.run("schema_version = 1\nname = 'x'\n")
    assert e.value.file == "<scenario text>"


def test_mujoco_runs_from_the_package_with_no_variable(monkeypatch):
    """The package finds the project's MuJoCo library (target/, built by scripts/setup-python)
    with no TOUCHDOWN_MUJOCO_LIBRARY: run, compare and view with their default engines."""
    for name in ("TOUCHDOWN_MUJOCO_LIBRARY", "TOUCHDOWN_HOME", "TOUCHDOWN_PYTHON"):
        monkeypatch.delenv(name, raising=False)
    flat = ROOT / "scenarios" / "flat-drop.toml"
    assert touchdown.run(flat, engine="mujoco")["summary"]["engine"] == "mujoco"
    engines = [e["name"] for e in touchdown.compare(flat)["engines"]]
    assert engines == ["core", "rapier", "mujoco"]


def test_mujoco_runs_from_the_package_installed_elsewhere_with_no_variable(tmp_path):
    """The package as pip installs it, outside the project (a copy of python/touchdown with its
    native module), run from a folder outside the project with no TOUCHDOWN_* variable: it
    finds the project it was built from, its MuJoCo library and its runner."""
    import os
    import shutil

    site = tmp_path / "site-packages"
    shutil.copytree(ROOT / "python" / "touchdown", site / "touchdown", ignore=shutil.ignore_patterns("__pycache__"))
    env = {k: v for k, v in os.environ.items() if not k.startswith("TOUCHDOWN_")}
    env["PYTHONPATH"] = str(site)
    code = (
        "import touchdown; "
        "print(touchdown.__file__); "
        f"print(touchdown.run({str(ROOT / 'scenarios' / 'flat-drop.toml')!r}, engine='mujoco')['summary']['engine'])"
    )
    out = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env=env, capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    module, engine = out.stdout.split()
    assert module.startswith(str(site)) and engine == "mujoco"


def test_the_mujoco_runner_refuses_a_mujoco_whose_data_it_does_not_know(tmp_path, monkeypatch):
    """The library's step loop reads the friction rows' address from mjData at the offset of
    the pinned MuJoCo; it checks that offset against the bindings' address before the first
    step, so a MuJoCo of another layout is refused by name, not written into at random."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("td_mujoco_runner", ROOT / "python" / "mujoco" / "run.py")
    runner = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(runner)
    lib = runner.load_library(str(ROOT / "target" / "release" / "libtouchdown_mujoco.so"))
    flat = str(ROOT / "scenarios" / "flat-drop.toml")
    monkeypatch.chdir(tmp_path)  # the runner works in its output folder
    runner.land(lib, flat, str(tmp_path / "right"))
    assert (tmp_path / "right" / "summary.json").is_file()
    real = runner.MjLoop

    def elsewhere(step1, step2, model, data, frictionloss, *rest):
        return real(step1, step2, model, data, frictionloss + 8, *rest)

    monkeypatch.setattr(runner, "MjLoop", elsewhere)
    with pytest.raises(runner.Failure, match="efc_frictionloss is not at byte 161568"):
        runner.land(lib, flat, str(tmp_path / "wrong"))


def test_a_path_that_names_no_file_is_file_not_found(tmp_path, monkeypatch):
    """A one-line string is a path (scenario text spans lines): a missing file raises
    FileNotFoundError naming the path and the working directory, never a TOML error."""
    monkeypatch.chdir(tmp_path)
    for call in (touchdown.run, touchdown.compare):
        with pytest.raises(FileNotFoundError) as e:
            call("scenarios/nope.toml")
        assert e.value.filename == "scenarios/nope.toml"
        assert str(tmp_path) in str(e.value)
    with pytest.raises(FileNotFoundError):
        touchdown.run("typo.tom")


def test_errors_carry_the_file_field_and_cause():
    with pytest.raises(touchdown.ScenarioInvalid) as e:
        touchdown.run(SCENARIO, overrides={"touchdown.vertical_speed": -10.0})
    assert e.value.field == "touchdown.vertical_speed"
    assert "unknown field `vertical_speed`" in e.value.message and "vertical_velocity" in e.value.message
    with pytest.raises(touchdown.ScenarioInvalid) as e:
        touchdown.run(SCENARIO, overrides={"touchdown.vertical_velocity": float("nan")})
    assert e.value.field == "touchdown.vertical_velocity"
    # A hostile field path (60,000 parts) is refused, never nested past the stack.
    with pytest.raises(touchdown.ScenarioInvalid) as e:
        touchdown.run(SCENARIO, overrides={".".join(["a"] * 60_000): 1.0})
    assert "a field path of 60000 parts" in e.value.message
    with pytest.raises(touchdown.TouchdownError):
        touchdown.run(SCENARIO, engine="bullet")


def test_a_shard_from_python_is_the_command_lines_byte_for_byte(tmp_path):
    small = str(ROOT / "scenarios" / "campaigns" / "small.toml")
    py = campaign.run_shard(small, 2, 4, tmp_path / "py")
    subprocess.run(
        [TOUCHDOWN, "campaign", small, "--shard", "2/4", "--out", tmp_path / "cli"],
        capture_output=True,
        check=True,
    )
    for name in ("manifest.json", "landings.jsonl", "landings.parquet", "statistics.json"):
        assert (py / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name


def test_campaign_arguments_of_the_wrong_kind_are_refused_by_name(tmp_path):
    """1.5 is not a shard number, 'no' is not False, one path is not a list of folders, a string
    is not a shard count: each a TypeError naming the argument, before anything runs."""
    import touchdown.dask

    small = str(ROOT / "scenarios" / "campaigns" / "small.toml")
    for call, name in [
        (lambda: campaign.run_shard(small, 1.5, 2, tmp_path / "a"), "k"),
        (lambda: campaign.run_shard(small, True, 2, tmp_path / "a"), "k"),
        (lambda: campaign.run_shard(small, 1, 2, tmp_path / "a", resume="no"), "resume"),
        (lambda: campaign.merge(str(tmp_path / "a"), tmp_path / "b"), "parts"),
        (lambda: touchdown.dask.run_campaign(None, small, "3", tmp_path / "c"), "shards"),
    ]:
        with pytest.raises(TypeError, match=f"^{name}: "):
            call()
    with pytest.raises(ValueError, match="^n: expected at least 1"):
        campaign.run_shard(small, 1, 0, tmp_path / "a")
    assert not any(tmp_path.iterdir()), "an argument refused after something was written"
    # The command line's limit on vertical velocities holds for Python's list too.
    with pytest.raises(ValueError, match="^vv: expected 1 to 10000 vertical velocities, got 10001"):
        touchdown.boundary(SCENARIO, [-1.0] * 10_001)


def test_scenario_text_with_extends_and_overrides_of_the_wrong_kind_are_refused_by_name():
    """Text cannot extend a file (its path would be relative to nothing); an override's name or
    value of the wrong kind, or a string with a lone surrogate, is refused naming the override."""
    with pytest.raises(touchdown.ScenarioInvalid) as e:
        touchdown.run('schema_version = 1\nextends = "scenarios/flat-drop.toml"\nname = "x"\n')
    assert "field `extends`: a scenario given as text cannot extend a file" in str(e.value)
    for overrides, error, says in [
        ({"name": "\udc80"}, ValueError, 'overrides["name"]: expected a string of valid Unicode'),
        ({"\udc80": 1.0}, TypeError, "overrides: expected field paths as strings"),
        ({"name": [1]}, TypeError, 'overrides["name"]: expected a number, a string or a boolean, got list'),
        ({3: 1.0}, TypeError, "overrides: expected field paths as strings"),
    ]:
        with pytest.raises(error) as e:
            touchdown.run(SCENARIO, overrides=overrides)
        assert says in str(e.value)


def test_python_entry_points_refuse_hostile_arguments_by_name(tmp_path, monkeypatch):
    """The Python entry points fuzzed: each argument of each call replaced, one at a time, by a
    value of another kind (None, a bool, a float where a whole number goes, a string where a list
    goes, a list where a string goes, a lone surrogate, NaN, an empty dict). Each call either
    runs or raises a TypeError or ValueError naming the argument, a TouchdownError (whose
    message names the file or the field) or, for a path that names no file, FileNotFoundError
    with the path: never anything else, and never a panic."""
    import itertools

    monkeypatch.chdir(tmp_path)
    small = str(ROOT / "scenarios" / "campaigns" / "small.toml")
    hostile = [None, True, 1.5, -1, "", "core", "\udc80", [], ["x"], {}, float("nan"), object()]
    calls = {
        "run": (touchdown.run, {"scenario": str(SCENARIO), "engine": "core", "overrides": {}, "history": False}),
        "compare": (touchdown.compare, {"scenario": str(SCENARIO), "engines": ["core", "core"], "overrides": {}}),
        "boundary": (
            touchdown.boundary,
            {"scenario": str(SCENARIO), "vv": [-8.0], "vh_step": 12.0, "vh_max": 12.0, "tol": 1.0, "engines": ["core"]},
        ),
        "run_shard": (campaign.run_shard, {"campaign": small, "k": 24, "n": 24, "out_dir": "shard", "resume": False}),
        "holds_shard": (campaign.holds_shard, {"campaign": small, "k": 1, "n": 2, "folder": "nothing"}),
        "merge": (campaign.merge, {"parts": ["nothing"], "out_dir": "merged"}),
    }
    outcomes = {}
    for name, (call, arguments) in calls.items():
        for argument, value in itertools.product(arguments, hostile):
            given = dict(arguments, **{argument: value})
            try:
                call(**given)
                outcome = "ran"
            except FileNotFoundError as e:
                # A path that names no file: the documented error, with the path.
                assert argument in ("scenario", "campaign") and e.filename == value, f"{name}({argument}={value!r}): {e}"
                outcome = "FileNotFoundError"
            except (TypeError, ValueError) as e:
                assert str(e).startswith(argument), f"{name}({argument}={value!r}): {type(e).__name__}: {e}"
                outcome = type(e).__name__
            except touchdown.TouchdownError as e:
                assert str(e), f"{name}({argument}={value!r}): an empty message"
                outcome = "TouchdownError"
            outcomes[outcome] = outcomes.get(outcome, 0) + 1
    assert outcomes.get("TypeError", 0) > 0 and outcomes.get("ran", 0) > 0, outcomes


def test_a_shard_folder_of_the_campaign_before_an_edit_is_not_taken_for_done(tmp_path):
    """A scheduler counts a shard done only when its folder holds that shard of the campaign as
    it is now (`holds_shard`, what `touchdown.dask.run_campaign` asks): after the campaign file
    is edited, the old shard is not reused, and running into its folder is refused by name."""
    text = (ROOT / "scenarios" / "campaigns" / "small.toml").read_text()
    base = ROOT / "scenarios" / "table-i-2-2-vv8.toml"
    text = text.replace('"../table-i-2-2-vv8.toml"', repr(str(base)).replace("'", '"'))
    file = tmp_path / "campaign.toml"
    file.write_text(text)
    out = tmp_path / "out"
    done = campaign.run_shard_atomically(str(file), 1, 2, str(out))
    assert campaign.holds_shard(file, 1, 2, done)
    assert not campaign.holds_shard(file, 2, 2, done)
    file.write_text(text.replace("seed = 7", "seed = 8"))
    assert not campaign.holds_shard(file, 1, 2, done)
    with pytest.raises(touchdown.TouchdownError, match="another campaign"):
        campaign.run_shard_atomically(str(file), 1, 2, str(out))


def cli_campaign(tmp_path, name="cli"):
    small = str(ROOT / "scenarios" / "campaigns" / "small.toml")
    subprocess.run([TOUCHDOWN, "campaign", small, "--out", tmp_path / name], capture_output=True, check=True)
    return small, tmp_path / name


FILES = ("manifest.json", "landings.jsonl", "landings.parquet", "statistics.json")


def test_a_campaign_on_a_local_dask_cluster_is_the_single_process_campaign(tmp_path):
    from dask.distributed import Client, LocalCluster

    import touchdown.dask

    small, whole = cli_campaign(tmp_path)
    out = tmp_path / "dask"
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0") as cluster:
        with Client(cluster) as client:
            touchdown.dask.run_campaign(client, small, shards=4, out_dir=out, progress=False)
    for name in FILES:
        assert (out / name).read_bytes() == (whole / name).read_bytes(), name


def test_a_resumed_campaign_runs_only_its_missing_shards(tmp_path):
    from dask.distributed import Client, LocalCluster

    import touchdown.dask
    from touchdown.campaign import shard_dir

    small, whole = cli_campaign(tmp_path)
    out = tmp_path / "dask"
    # Shards 1 and 3 finished before the interruption; a marker in each shows if it is redone.
    for k in (1, 3):
        campaign.run_shard_atomically(small, k, 4, str(out))
        (shard_dir(out, k, 4) / "kept").write_text("")
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0") as cluster:
        with Client(cluster) as client:
            touchdown.dask.run_campaign(client, small, shards=4, out_dir=out, progress=False)
    assert all((shard_dir(out, k, 4) / "kept").exists() for k in (1, 3))
    for name in FILES:
        assert (out / name).read_bytes() == (whole / name).read_bytes(), name


def _dies_once(marker, campaign_file, k, n, out_dir):
    """A shard whose first attempt kills its worker process."""
    import os
    from pathlib import Path

    if not Path(marker).exists():
        Path(marker).write_text("")
        os._exit(1)
    return campaign.run_shard_atomically(campaign_file, k, n, out_dir)


def test_a_shard_whose_worker_dies_is_run_again(tmp_path):
    from dask.distributed import Client, LocalCluster

    small, whole = cli_campaign(tmp_path)
    out = tmp_path / "dask"
    marker = tmp_path / "died"
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0") as cluster:
        with Client(cluster) as client:
            f = client.submit(_dies_once, str(marker), small, 2, 4, str(out), retries=2, pure=False)
            assert client.gather(f) == str(campaign.shard_dir(out, 2, 4))
    assert marker.exists()
    assert (campaign.shard_dir(out, 2, 4) / "landings.parquet").exists()


def test_a_shard_killed_part_way_resumes_to_the_command_lines_bytes(tmp_path):
    """A shard's process killed part-way (SIGKILL, as a lost Dask worker) leaves the records it
    finished; the next attempt (`run_shard_atomically`, as a retried task) goes on from them and
    ends with the command line's shard, byte for byte."""
    import signal
    import time

    file = str(ROOT / "scenarios" / "campaigns" / "lm-1-6-d3117.toml")
    cli = tmp_path / "cli"
    subprocess.run([TOUCHDOWN, "campaign", file, "--shard", "1/4", "--out", cli], capture_output=True, check=True)
    out = tmp_path / "dask"
    final = campaign.shard_dir(out, 1, 4)
    records = final.with_name(final.name + ".partial") / "landings.jsonl"
    code = f"from touchdown import campaign; campaign.run_shard_atomically({file!r}, 1, 4, {str(out)!r})"
    attempt = subprocess.Popen([sys.executable, "-c", code])
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and not (records.exists() and records.stat().st_size > 0):
        time.sleep(0.01)
    time.sleep(0.3)
    attempt.send_signal(signal.SIGKILL)
    attempt.wait()
    assert not final.exists(), "the shard (750 landings) finished before the kill"
    kept = records.read_bytes()
    kept = kept[: kept.rfind(b"\n") + 1]
    assert kept.count(b"\n") > 0
    assert campaign.run_shard_atomically(file, 1, 4, str(out)) == str(final)
    for name in FILES:
        assert (final / name).read_bytes() == (cli / name).read_bytes(), name
    assert (final / "landings.jsonl").read_bytes().startswith(kept)


def test_the_history_as_a_pandas_or_polars_frame():
    arrays = touchdown.run(SCENARIO)["history"]
    pandas_frame = touchdown.run(SCENARIO, frame="pandas")["history"]
    polars_frame = touchdown.run(SCENARIO, frame="polars")["history"]
    assert list(pandas_frame.columns) == list(arrays) == polars_frame.columns
    for name in ("t_s", "leg1_primary_stroke_m", "z_m"):
        assert np.array_equal(pandas_frame[name].to_numpy(), arrays[name])
        assert np.array_equal(polars_frame[name].to_numpy(), arrays[name])
    with pytest.raises(ValueError, match="frame"):
        touchdown.run(SCENARIO, frame="arrow")


def test_a_comparison_is_the_command_lines():
    flat = ROOT / "scenarios" / "flat-drop.toml"
    cli = subprocess.run(
        [TOUCHDOWN, "compare", flat, "--engines", "core,rapier", "--format", "json", "--report-only"],
        capture_output=True,
        check=True,
    )
    import json

    py = touchdown.compare(flat, engines=["rapier", "core"])
    assert py == json.loads(cli.stdout)  # the one line of JSON Lines, for one scenario
    assert [e["name"] for e in py["engines"]] == ["core", "rapier"]
    assert py["schema"] == "touchdown.compare/1" and py["settings"]["engines"] == ["core", "rapier"]
    with pytest.raises(touchdown.TouchdownError, match=r"at least two engines to compare \(got core\)$"):
        touchdown.compare(flat, engines=["core", "core"])


def test_a_view_is_the_command_lines(tmp_path):
    scenario = ROOT / "scenarios" / "table-i-2-2-vv8.toml"
    subprocess.run(
        [TOUCHDOWN, "view", scenario, "--engines", "core,rapier", "--set", "touchdown.vertical_velocity=-9.0",
         "--out", tmp_path],
        capture_output=True,
        check=True,
    )
    v = touchdown.view(scenario, engines=["rapier", "core"], overrides={"touchdown.vertical_velocity": -9.0})
    assert v["html"] == (tmp_path / "table-i-2-2-vv8.html").read_text(encoding="utf-8")
    import json

    assert v["trajectory"] == json.loads((tmp_path / "table-i-2-2-vv8.trajectory.json").read_text())
    assert [e["name"] for e in v["trajectory"]["engines"]] == ["core", "rapier"]
    with pytest.raises(ValueError, match="frame_interval: expected a time between frames > 0 s"):
        touchdown.view(scenario, frame_interval=0.0)
    with pytest.raises(touchdown.TouchdownError, match="none of the engines asked for"):
        touchdown.view(ROOT / "scenarios" / "slosh-drop.toml", engines=["rapier"])


def test_a_boundary_is_the_command_lines_and_overrides_move_it():
    cli = subprocess.run(
        [TOUCHDOWN, "boundary", SCENARIO, "--vv=-8:-10:2", "--vh-step", "4", "--vh-max", "16", "--format", "json"],
        capture_output=True,
        check=True,
    )
    import json

    py = touchdown.boundary(SCENARIO, vv=[-8.0, -10.0], vh_step=4.0, vh_max=16.0)
    # The same documents but for how the scenario was named: the settings as given.
    for p in py:
        p["scenario"]["path"] = str(SCENARIO)
    cli_points = [json.loads(line) for line in cli.stdout.splitlines()]
    for p in cli_points:
        p["scenario"]["path"] = str(SCENARIO)
        p["settings"]["vv_ft_s"] = [-8.0, -10.0]
    assert py == cli_points
    assert [p["engine"] for p in py] == ["core", "core"]
    assert [p["vv_m_s"] for p in py] == [-8.0 * 0.3048, -10.0 * 0.3048]
    # Every point says where a strut first goes past its capacity and how far the landing is safe.
    for p in py:
        assert p["safe"]["safe_to_vh_m_s"] <= p.get("vh_m_s", p["stable_at_vh_m_s"])
    # Once per end-stop law, each point naming its law.
    laws = touchdown.boundary(SCENARIO, vv=[-8.0], vh_step=4.0, vh_max=16.0, stop_restitution=[0.5, 1.0])
    assert [p["stop_restitution"] for p in laws] == [0.5, 1.0]
    # One vertical velocity may be given as a number.
    [one] = touchdown.boundary(SCENARIO, vv=-8.0, vh_step=4.0, vh_max=16.0)
    assert one["settings"]["vv_ft_s"] == [-8.0]
    assert {k: v for k, v in one.items() if k != "settings"} == {k: v for k, v in py[0].items() if k != "settings"}
    assert laws[0]["settings"]["stop_restitution"] == [0.5, 1.0]
    with pytest.raises(ValueError, match="vh_step"):
        touchdown.boundary(SCENARIO, vv=[-8.0], vh_step=0.0)
    with pytest.raises(ValueError, match="stop_restitution"):
        touchdown.boundary(SCENARIO, vv=[-8.0], stop_restitution=[1.5])
    with pytest.raises(ValueError, match="negative down"):
        touchdown.boundary(SCENARIO, vv=[8.0])
    with pytest.raises(touchdown.ScenarioInvalid) as e:
        touchdown.boundary(SCENARIO, vv=[-8.0], overrides={"touchdown.vertical_speed": 1.0})
    assert e.value.field == "touchdown.vertical_speed"
    # A scenario with no horizontal velocity gives the search no direction to run along.
    with pytest.raises(touchdown.ScenarioInvalid) as e:
        touchdown.boundary(ROOT / "scenarios" / "tripod-drop.toml", vv=[-8.0])
    assert e.value.field == "touchdown.horizontal_velocity" and "non-zero" in str(e.value)


def test_a_landing_leaves_the_interpreter_free_for_other_threads():
    """While a landing runs in one thread, another thread keeps running Python: the calls
    release the interpreter's lock. Landings of several threads equal the same landings run
    one after the other."""
    import threading
    import time

    window = {}

    def land():
        window["start"] = time.perf_counter()
        window["summary"] = touchdown.run(SCENARIO, engine="rapier", history=False)["summary"]
        window["end"] = time.perf_counter()

    ticks = []
    worker = threading.Thread(target=land)
    worker.start()
    while worker.is_alive():
        ticks.append(time.perf_counter())
    worker.join()
    inside = [t for t in ticks if window["start"] <= t <= window["end"]]
    duration = window["end"] - window["start"]
    gaps = np.diff([window["start"], *inside, window["end"]])
    # Were the lock held for the whole landing, this thread would stall for all of it.
    assert gaps.max() < 0.5 * duration, (gaps.max(), duration)

    from concurrent.futures import ThreadPoolExecutor

    speeds = [-6.0, -8.0, -10.0, -12.0]
    one_by_one = [
        touchdown.run(SCENARIO, overrides={"touchdown.vertical_velocity": v}, history=False)["summary"]
        for v in speeds
    ]
    with ThreadPoolExecutor(max_workers=2) as pool:
        threaded = list(
            pool.map(
                lambda v: touchdown.run(SCENARIO, overrides={"touchdown.vertical_velocity": v}, history=False)[
                    "summary"
                ],
                speeds,
            )
        )
    assert threaded == one_by_one


def test_the_worked_example_regenerates_its_data(tmp_path):
    """docs/python/dispersion_study.py, run as a script, writes the data committed beside the
    figure of docs/python.md, byte for byte."""
    example = ROOT / "docs" / "python" / "dispersion_study.py"
    subprocess.run([sys.executable, example, "--out", tmp_path], capture_output=True, check=True)
    committed = ROOT / "docs" / "python" / "dispersion-study.json"
    assert (tmp_path / "dispersion-study.json").read_bytes() == committed.read_bytes()
    assert (tmp_path / "dispersion-study.png").stat().st_size > 10_000


def test_a_paired_campaigns_records_line_up_engine_by_engine(tmp_path):
    """A paired campaign (core and rapier, three landings run 0.2 s) read back as one frame
    with a block per engine, and as one frame per engine under the single-engine names; an
    engine it did not land on is refused by name."""
    text = (ROOT / "scenarios" / "campaigns" / "small.toml").read_text()
    text = text.replace('scenario = "../', f'scenario = "{ROOT / "scenarios"}/')
    text = text.replace('engine = "core"', 'engines = ["core", "rapier"]').replace("landings = 24", "landings = 3")
    text = text.replace(
        "\n[[correlation]]",
        '\n[[dispersion]]\nfield = "integrator.t_end"\nunit = "s"\ndistribution = "list"\nvalues = [0.2]\n\n[[correlation]]',
        1,
    )
    text = text.replace("histories = [3]", "histories = []")
    file = tmp_path / "paired.toml"
    file.write_text(text)
    out = tmp_path / "out"
    subprocess.run([TOUCHDOWN, "campaign", file, "--out", out], capture_output=True, check=True)
    both = campaign.records(out)
    assert list(both["landing"]) == [0, 1, 2]
    assert {"core.outcome", "rapier.outcome", "rapier.leg1.primary.stroke_m"} <= set(both.columns)
    core, rapier = campaign.records(out, "core"), campaign.records(out, "rapier")
    assert list(core.columns) == list(rapier.columns)
    assert "leg1.primary.stroke_m" in core.columns and "outcome" in core.columns
    assert (rapier["leg1.primary.stroke_m"] == both["rapier.leg1.primary.stroke_m"]).all()
    with pytest.raises(ValueError, match="landed on core, rapier"):
        campaign.records(out, "mujoco")
