"""The Python package `touchdown` (python/touchdown, crates/python), run by scripts/test."""

import subprocess
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


def test_the_summary_is_the_command_lines():
    cli = subprocess.run([TOUCHDOWN, "run", SCENARIO, "--format", "json"], capture_output=True, check=True)
    import json

    assert touchdown.run(SCENARIO, history=False)["summary"] == json.loads(cli.stdout)


def test_overrides_and_text_change_the_landing():
    base = touchdown.run(SCENARIO, history=False)["summary"]
    faster = touchdown.run(SCENARIO, overrides={"touchdown.vertical_velocity": -10.0}, history=False)["summary"]
    assert faster["max_primary_stroke_m"][0] > base["max_primary_stroke_m"][0]
    flat = (ROOT / "scenarios" / "flat-drop.toml").read_text()
    assert "extends" in flat
    with pytest.raises(touchdown.ScenarioInvalid) as e:
        touchdown.run("schema_version = 1\nname = 'x'\n")
    assert e.value.file == "<scenario text>"


def test_errors_carry_the_file_field_and_cause():
    with pytest.raises(touchdown.ScenarioInvalid) as e:
        touchdown.run(SCENARIO, overrides={"touchdown.vertical_speed": -10.0})
    assert e.value.field == "touchdown.vertical_speed"
    assert "no field `vertical_speed`" in e.value.message
    with pytest.raises(touchdown.ScenarioInvalid) as e:
        touchdown.run(SCENARIO, overrides={"touchdown.vertical_velocity": float("nan")})
    assert e.value.field == "touchdown.vertical_velocity"
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
