"""Every machine-readable output against its documented schema (docs/outputs.md,
docs/schemas/): real output of the command line and of the Python package, and the documents
committed under docs/. Run by scripts/test."""

import json
import re
import subprocess
from pathlib import Path

import pytest
from jsonschema import Draft202012Validator
from referencing import Registry, Resource

import touchdown

ROOT = Path(__file__).resolve().parents[2]
TOUCHDOWN = ROOT / "target" / "debug" / "touchdown"
SCHEMAS = ROOT / "docs" / "schemas"


def _schemas() -> dict:
    found = {}
    for path in sorted(SCHEMAS.glob("*.schema.json")):
        schema = json.loads(path.read_text(encoding="utf-8"))
        Draft202012Validator.check_schema(schema)
        found[schema["$id"]] = schema
    return found


ALL = _schemas()
REGISTRY = Registry().with_resources([(i, Resource.from_contents(s)) for i, s in ALL.items()])


def _refuse_constant(name):
    raise ValueError(f"{name} in a document")


def parse(text: str) -> dict:
    """One JSON document; NaN and infinities are refused (JSON has none)."""
    return json.loads(text, parse_constant=_refuse_constant)


def lines(text: str) -> list:
    return [parse(line) for line in text.splitlines() if line.strip()]


def nulls(value, where="") -> list:
    """The paths of every null in `value`."""
    if value is None:
        return [where or "/"]
    if isinstance(value, dict):
        return [p for k, v in value.items() for p in nulls(v, f"{where}/{k}")]
    if isinstance(value, list):
        return [p for i, v in enumerate(value) for p in nulls(v, f"{where}/{i}")]
    return []


def errors(document: dict) -> list:
    """What is wrong with `document` against the schema its `schema` field names."""
    m = re.fullmatch(r"touchdown\.([a-z-]+)/1", document.get("schema", ""))
    assert m, f"no `schema` field naming a document: {str(document)[:200]}"
    schema = ALL.get(f"urn:touchdown:{m.group(1)}")
    assert schema is not None, f"docs/schemas has no {m.group(1)}.schema.json"
    validator = Draft202012Validator(schema, registry=REGISTRY)
    return [f"/{'/'.join(map(str, e.absolute_path))}: {e.message[:300]}" for e in validator.iter_errors(document)]


def check(document: dict, kind: str) -> None:
    assert document["schema"] == f"touchdown.{kind}/1"
    assert not errors(document), errors(document)
    assert not nulls(document), nulls(document)


def cli(*args: str) -> str:
    out = subprocess.run([TOUCHDOWN, *args], capture_output=True, check=False, cwd=ROOT)
    assert out.returncode == 0, out.stderr.decode()
    return out.stdout.decode()


def test_every_schema_is_documented_and_refers_to_the_envelope():
    page = (ROOT / "docs" / "outputs.md").read_text(encoding="utf-8")
    for path in SCHEMAS.glob("*.schema.json"):
        assert f"(schemas/{path.name})" in page, f"docs/outputs.md does not link {path.name}"
    for i, schema in ALL.items():
        if i != "urn:touchdown:envelope":
            assert {"$ref": "urn:touchdown:envelope"} in schema["allOf"], i
            assert schema["unevaluatedProperties"] is False, i


def test_a_schema_refuses_what_it_does_not_describe():
    run = parse(cli("run", "scenarios/flat-drop.toml", "--format", "json"))
    check(run, "run")
    for change in (
        lambda d: d.update(max_stroke_in=[1.0]),  # a field the schema does not list
        lambda d: d.pop("energy_residual_j"),  # a required field missing
        lambda d: d["energy"].update(friction_j=0.0),  # nested, too
        lambda d: d["scenario"].update(sha256="not a hash"),  # the envelope is checked
        lambda d: d.update(outcome="tipped"),  # an outcome that does not exist
    ):
        broken = json.loads(json.dumps(run))
        change(broken)
        assert errors(broken), "the schema should refuse it"


def test_run_documents(tmp_path):
    scenario = "scenarios/table-i-2-2-vv8.toml"
    printed = parse(cli("run", scenario, "--format", "json", "--set", "touchdown.vertical_velocity=-9.0",
                        "--out", str(tmp_path)))
    check(printed, "run")
    assert printed["settings"]["set"] == [{"field": "touchdown.vertical_velocity", "value": -9.0}]
    assert printed == parse((tmp_path / "summary.json").read_text())
    # With a mechanism (its evaluations), an overturn (its velocity), on a multibody engine.
    check(parse(cli("run", "scenarios/curb-slide.toml", "--format", "json")), "run")
    overturn = parse(cli("run", "scenarios/near-boundary-overturn.toml", "--format", "json", "--engine", "rapier"))
    check(overturn, "run")
    assert overturn["outcome"] == "unstable" and "overturn_velocity_m_s" in overturn
    check(touchdown.run(ROOT / scenario, history=False)["summary"], "run")
    # With the rounding ensemble: the 2-2 landing at 6 ft/s names the uphill legs' struts it
    # rocks back onto (docs/engines.md, "Rounding-decided channels").
    rounded = parse(cli("run", "scenarios/table-i-2-2-vv6.toml", "--format", "json", "--rounding"))
    check(rounded, "run")
    named = {(u["leg"], u["strut"]) for u in rounded["rounding"]["undetermined"]}
    assert named == {(3, "primary"), (4, "primary"), (3, "sec31"), (4, "sec41")}, rounded["rounding"]
    from_python = touchdown.run(ROOT / "scenarios" / "table-i-2-2-vv6.toml", history=False, rounding=True)["summary"]
    check(from_python, "run")
    assert from_python["rounding"] == rounded["rounding"]


def test_check_documents():
    clean = parse(cli("check", "scenarios/flat-drop.toml", "--format", "json"))
    check(clean, "check")
    assert clean["findings"] == [] and clean["figures"]["stroke_energy_of_touchdown"] > 1
    steep = touchdown.check(ROOT / "scenarios/flat-drop.toml", overrides={"surface.slope": 70.0})
    check(steep, "check")
    assert [f["concern"] for f in steep["findings"]] == ["value", "tip_over"]


def test_compare_streams_one_document_per_scenario(tmp_path):
    out = cli("compare", "scenarios/flat-drop.toml", "scenarios/level-sliding.toml", "--engines", "core,rapier",
              "--format", "json", "--report-only", "--out", str(tmp_path))
    docs = lines(out)
    assert [d["scenario"]["path"] for d in docs] == ["scenarios/flat-drop.toml", "scenarios/level-sliding.toml"]
    for d in docs:
        check(d, "compare")
        assert d["settings"] == {"engines": ["core", "rapier"], "set": []}
    channels = docs[1]["pairs"][0]["channels"]
    assert {"quantity": "secondary_stroke", "leg": 2, "strut": "sec31"}.items() <= channels[6].items()
    assert docs[1] == parse((tmp_path / "level-sliding.json").read_text())
    check(touchdown.compare(ROOT / "scenarios" / "flat-drop.toml", engines=["core", "rapier"]), "compare")


def test_boundary_streams_one_document_per_point(tmp_path):
    out = cli("boundary", "scenarios/fig-25-26.toml", "--vv=-8:-10:2", "--vh-step", "4", "--vh-max", "16",
              "--tol", "0.5", "--format", "json", "--out", str(tmp_path))
    docs = lines(out)
    assert [d["vv_m_s"] for d in docs] == [-8.0 * 0.3048, -10.0 * 0.3048]
    for d in docs:
        check(d, "boundary")
        assert d["settings"]["vh_step_ft_s"] == 4.0 and d["settings"]["vv_ft_s"] == [-8.0, -10.0]
    assert docs == lines((tmp_path / "boundary-fig-25-26.jsonl").read_text())


def test_the_validation_documents(tmp_path):
    check(parse(cli("validate", "--format", "json", "--report-only", "--out", str(tmp_path))), "validate")
    check(parse((tmp_path / "fig-25-26-series.json").read_text()), "series")
    sensitivity = parse(cli("sensitivity", "--fraction", "0.2", "--format", "json"))
    check(sensitivity, "sensitivity")


def test_precision_and_robustness(tmp_path):
    check(parse(cli("precision", "scenarios/flat-drop.toml", "--engines", "core", "--rungs", "1", "--repeats", "1",
                    "--format", "json", "--out", str(tmp_path))), "precision")
    check(parse((tmp_path / "precision-flat-drop.json").read_text()), "precision")
    # Every core case completes since the sliding footpads were corrected with the vehicle
    # (friction-0 was the one the energy guard stopped); rapier refuses rates x100 by name.
    robustness = parse(cli("robustness", "--engines", "core,rapier", "--cases", "onset-x100", "--format", "json"))
    check(robustness, "robustness")
    assert {(r["engine"], r["verdict"]) for r in robustness["runs"]} == {("core", "completed"), ("rapier", "refused")}
    # A stopped run's diagnostic: the first unstable step of the largest-stable-step search.
    searched = parse(cli("robustness", "--engines", "core", "--cases", "onset-x1000", "--search", "--format", "json"))
    check(searched, "robustness")
    assert all("simulation stopped at t =" in s["first_unstable"]["why"] for s in searched["steps"])


def test_precision_on_a_campaign_mix(tmp_path):
    campaign = tmp_path / "drops.toml"
    campaign.write_text(
        'schema_version = 1\nname = "flat drops"\ndescription = "two descent speeds"\n'
        f'scenario = "{ROOT / "scenarios" / "flat-drop.toml"}"\nengine = "core"\nlandings = 2\nseed = 1\n'
        'confidence = 0.9\n\n[[dispersion]]\nfield = "touchdown.vertical_velocity"\nunit = "ft/s"\n'
        'distribution = "uniform"\nmin = -9.0\nmax = -7.0\n')
    mix = parse(cli("precision", str(campaign), "--landings", "2", "--engines", "core", "--rungs", "1",
                    "--repeats", "1", "--format", "json", "--out", str(tmp_path)))
    check(mix, "precision-mix")
    assert parse((tmp_path / "precision-drops.json").read_text()) == mix, "the file is the document printed"
    assert [r["landing"] for r in mix["references"]] == ["landing 0", "landing 1"]


def embedded_trajectory(page: Path) -> dict:
    """The trajectory document a view page plays (its `<script id="trajectory">`)."""
    html = page.read_text(encoding="utf-8")
    m = re.search(r'<script type="application/json" id="trajectory">(.*?)</script>', html, re.S)
    assert m, f"{page}: no embedded trajectory"
    return parse(m.group(1).replace("<\\/", "</"))


def test_view_writes_a_trajectory_and_its_page(tmp_path):
    out = cli("view", "scenarios/curb-slide.toml", "--engines", "core", "--frame-interval", "0.005",
              "--set", "touchdown.vertical_velocity=-9.0", "--out", str(tmp_path))
    assert "curb-slide.html" in out
    document = parse((tmp_path / "curb-slide.trajectory.json").read_text())
    check(document, "trajectory")
    assert document["settings"] == {"engines": ["core"], "frame_interval_s": 0.005,
                                    "set": [{"field": "touchdown.vertical_velocity", "value": -9.0}]}
    core = document["engines"][0]
    assert core["curbs"] and core["events"]
    frames = core["frames"]
    assert all(len(v) == len(frames["t_s"]) for k, v in frames.items() if k not in ("legs", "walls"))
    assert document == embedded_trajectory(tmp_path / "curb-slide.html")
    # A comparison's pages: one per scenario, every engine that ran.
    cli("compare", "scenarios/flat-drop.toml", "scenarios/level-sliding.toml", "--engines", "core,rapier",
        "--report-only", "--view", str(tmp_path / "view"))
    for name in ("flat-drop", "level-sliding"):
        document = parse((tmp_path / "view" / f"{name}.trajectory.json").read_text())
        check(document, "trajectory")
        assert [e["name"] for e in document["engines"]] == ["core", "rapier"]
        assert document == embedded_trajectory(tmp_path / "view" / f"{name}.html")


@pytest.mark.parametrize(
    "path",
    sorted(
        p.relative_to(ROOT).as_posix()
        for folder in ("docs/validation", "docs/engines", "docs/performance")
        for p in (ROOT / folder).glob("*.json*")
    ),
)
def test_the_committed_documents(path):
    """The data committed beside the docs' plots is real output of the current schemas."""
    text = (ROOT / path).read_text(encoding="utf-8")
    docs = lines(text) if path.endswith(".jsonl") else [parse(text)]
    assert docs
    for d in docs:
        assert not errors(d), (path, errors(d)[:5])
        assert not nulls(d), (path, nulls(d)[:5])
