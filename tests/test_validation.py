"""The validation harness: the quick subset passes, and a deliberately broken model fails it."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from numba import njit

import sawdrift as sd
from sawdrift.contact import KernelPair
from sawdrift.validation import Case, CaseResult, load_cases, validate
from sawdrift_builtin.mmd import MemoryDiagramModel

_mmd_force = MemoryDiagramModel.kernel.force


@njit
def _flipped_force(fs, is_, pp, a, b, adot, bdot):
    # the memory-diagram law with the sign of the friction force flipped
    n, t = _mmd_force(fs, is_, pp, a, b, adot, bdot)
    return n, -t


class FlippedFriction(MemoryDiagramModel):
    """``mmd`` whose compiled kernel returns (N*, -T*): friction pushes instead of resisting."""

    name = "mmd_flipped_friction"
    summary = "deliberately broken: mmd with the friction sign flipped (tests only)"
    kernel = KernelPair(reset=MemoryDiagramModel.kernel.reset, force=_flipped_force)


@pytest.fixture
def flipped_model():
    sd.registry.register(FlippedFriction)
    try:
        yield FlippedFriction.name
    finally:
        sd.registry.unregister(FlippedFriction.name)


@pytest.mark.slow
def test_quick_subset_passes_and_writes_the_report(tmp_path):
    report = validate(tmp_path, quick=True, progress=False)
    failed = [(r.name, r.status, r.message) for r in report.results if r.failed]
    assert report.passed, failed
    assert report.results and all(r.status for r in report.results)
    html = (tmp_path / "index.html").read_text()
    assert "passed" in html and "data:image/png;base64," in html
    data = json.loads((tmp_path / "results.json").read_text())
    assert data["passed"] is True
    assert data["counts"]["failed"] == 0
    assert data["counts"]["total"] == len(report.results)
    groups = {c["group"] for c in data["cases"]}
    assert {"material_point", "mindlin", "convergence", "diagrams", "point_mass"} <= groups
    # models that are not exact by design are shown as expected deviations, with their value
    devs = [c for c in data["cases"] if c["status"] == "expected deviation"]
    assert devs and all(c["value"] is not None and c["model"] for c in devs)
    assert all(r.seconds >= 0 for r in report.results)


@pytest.mark.slow
def test_oracles_catch_a_flipped_friction_sign(tmp_path, flipped_model):
    # the mindlin oracles and the kernel-against-reference check, run for the broken model only
    report = validate(tmp_path, only=["mindlin", "kernel_vs_reference"], models=[flipped_model],
                      progress=False)
    assert not report.passed
    by_case = {r.case: r for r in report.results}
    assert set(by_case) == {"cm_monotonic", "cm_masing", "cm_loop_area", "cm_proportional",
                            "cm_random_history", "kernel_vs_reference"}
    for res in report.results:
        assert res.model == flipped_model
        assert res.status == "fail", (res.name, res.status, res.message)
        assert res.value > res.tolerance
    assert "FAIL" in (tmp_path / "index.html").read_text()


def _cases(tmp_path, **sources: str):
    """A folder of case files ``NAME.py`` with the given sources."""
    cases = tmp_path / "cases"
    cases.mkdir()
    for name, source in sources.items():
        (cases / f"{name}.py").write_text(source)
    return cases


def test_missing_model_and_broken_case_file_are_errors_not_crashes(tmp_path):
    cases = _cases(tmp_path, good=(
        "from sawdrift.validation import Case\n"
        "CASE = Case(name='good', group='convergence', title='1 <= 2', tolerance=2.0, quick=True,\n"
        "            models=('mmd', 'no_such_model'))\n"
        "def run(model):\n"
        "    return CASE.result(1.0, model=model, message='ok')\n"))
    (cases / "raises.py").write_text(
        "from sawdrift.validation import Case\n"
        "CASE = Case(name='raises', group='convergence', title='raises', tolerance=0.0, quick=True)\n"
        "def run():\n"
        "    raise RuntimeError('boom')\n"
    )
    (cases / "broken.py").write_text("this is not python\n")
    (cases / "_helper.py").write_text("raise SystemExit('helpers are not cases')\n")
    assert len(load_cases(cases)) == 3
    report = validate(tmp_path / "out", quick=True, cases_dir=cases, progress=False)
    status = {r.name: r.status for r in report.results}
    assert status == {"good[mmd]": "pass", "good[no_such_model]": "error", "raises": "error",
                      "broken": "error"}
    assert "no_such_model" in report.get("good[no_such_model]").message
    assert "boom" in report.get("raises").message
    assert not report.passed
    assert (tmp_path / "out" / "index.html").exists()
    data = json.loads((tmp_path / "out" / "results.json").read_text())
    assert data["counts"] == {"passed": 1, "failed": 3, "errors": 3, "expected_deviations": 0,
                              "skipped": 0, "total": 4}


def _deviation_case(tmp_path, models: str, flagged: str, result: str):
    """validate() of one case 'dev' over ``models``, ``flagged`` deviating by design, whose run
    returns ``result`` (the CASE.result call)."""
    cases = tmp_path / "cases"
    cases.mkdir()
    (cases / "dev.py").write_text(
        "from sawdrift.validation import Case\n"
        f"CASE = Case(name='dev', group='mindlin', title='x', tolerance=1e-9, models={models},\n"
        f"            expected_deviation={flagged})\n"
        "def run(model):\n"
        f"    return {result}\n"
    )
    return validate(tmp_path / "out", cases_dir=cases, progress=False)


def test_expected_deviation_is_reported_not_failed(tmp_path):
    report = _deviation_case(tmp_path, "('mmd', 'jaeger')", "('jaeger',)",
                             "CASE.result(0.25, model=model)")
    assert {r.name: r.status for r in report.results} == {"dev[mmd]": "fail",
                                                          "dev[jaeger]": "expected deviation"}
    assert report.get("dev[jaeger]").value == 0.25
    assert report.count("expected deviation") == 1 and not report.passed


def test_an_expected_deviation_must_be_its_own_closed_form(tmp_path):
    """A model flagged as deviating by design fails where the case finds it off its documented
    deviation's closed form (deviation_matches False): any value passed as 'expected' before."""
    report = _deviation_case(tmp_path, "('jaeger', 'mdr')", "('jaeger', 'mdr')",
                             "CASE.result(0.25, model=model, deviation_matches=model == 'jaeger')")
    assert {r.name: r.status for r in report.results} == {"dev[jaeger]": "expected deviation",
                                                          "dev[mdr]": "fail"}
    assert "not even the deviation expected by design" in report.get("dev[mdr]").message


def test_the_dem_spring_and_jaeger_follow_their_documented_deviations():
    """hertz_mindlin_dem in the Mindlin cases and jaeger under proportional loading are checked
    against their own closed forms (the DEM spring's straight line to its cap, its loop
    4 N* (B - N*/k); jaeger's N*(a*) - N*((1 - lambda) a*)), to 1e-9 (loop 1e-4)."""
    import importlib.util

    from sawdrift.validation import default_cases_dir

    for name, model in (("g2a_cm_monotonic", "hertz_mindlin_dem"),
                        ("g2b_cm_masing", "hertz_mindlin_dem"),
                        ("g2c_cm_loop_area", "hertz_mindlin_dem"),
                        ("g2d_cm_proportional", "jaeger")):
        spec = importlib.util.spec_from_file_location(name, default_cases_dir() / f"{name}.py")
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        result = module.run(model)
        assert not result.passed and result.deviation_matches is True, (name, result.message)


def test_expected_deviation_states_its_declared_reason(tmp_path):
    """Each expected deviation carries the case's one-line reason into the page and results.json."""
    cases = _cases(tmp_path, dev=(
        "from sawdrift.validation import Case\n"
        "CASE = Case(name='dev', group='mindlin', title='x', tolerance=1e-9,\n"
        "            models=('mmd', 'jaeger', 'mdr'), expected_deviation=('jaeger', 'mdr'),\n"
        "            deviation_reason={'jaeger': 'exact only at  constant a*'})\n"
        "def run(model):\n"
        "    return CASE.result(0.0 if model == 'mmd' else 0.25, model=model, message='W = 1.3')\n"))
    report = validate(tmp_path / "out", cases_dir=cases, progress=False)
    assert report.get("dev[jaeger]").deviation_reason == "exact only at constant a*"
    assert report.get("dev[mmd]").deviation_reason == ""
    data = json.loads((tmp_path / "out" / "results.json").read_text())
    rows = {c["name"]: c for c in data["cases"]}
    assert rows["dev[jaeger]"]["deviation_reason"] == "exact only at constant a*"
    assert rows["dev[mmd]"]["deviation_reason"] == ""
    assert data["expected_deviations"] == [
        {"name": "dev[jaeger]", "reason": "exact only at constant a*"},
        {"name": "dev[mdr]", "reason": "no reason declared by the case"}]
    page = (tmp_path / "out" / "index.html").read_text()
    assert "Not exact by design:</b> exact only at constant a*<br>W = 1.3" in page
    assert "Not exact by design:</b> no reason declared by the case" in page
    assert page.count("Not exact by design") == 2


def test_every_shipped_expected_deviation_declares_its_reason():
    """No shipped case marks a model as deviating by design without saying why."""
    declared = 0
    for lc in load_cases():
        case = lc.case
        if case.expected_deviation is False:
            continue
        models = case.models if case.models else (None,)
        for model in models:
            if case.deviation_expected(model):
                declared += 1
                assert len(case.reason_for(model)) > 20, (case.name, model)
    # six: lammps_chains no longer declares its whole case (it judges every chain but the two
    # impact-limited ones it names)
    assert declared >= 6


def test_steady_message_states_the_judged_quantity_first():
    """The message of steady_vs_full_inertia leads with the value it is judged on.

    The worst relative error over all cells can sit in a cell inside the absolute bound (a tiny
    creep speed); it must not read as the judged value.
    """
    from sawdrift.validation.cases import g9c_steady_vs_full_inertia as steady

    def row(key, ref, got):
        err = abs(got - ref)
        return {"key": key, "kind": "creep", "reference": ref, "default": got, "abs_error": err,
                "rel_error": err / abs(ref), "within": err <= max(1e-3 * abs(ref), 2e-5),
                "same_regime": True, "regime": "creep", "regime_ref": "creep"}

    rows = [row("jaeger/m10000", -1.47406e-6, -6.0865e-6), row("mmd/m30", 0.2, 0.2000424)]
    msg = steady.judged_message(rows)
    assert msg.startswith("worst relative error among the cells outside the 2e-5 absolute bound "
                          "2.12e-04 at mmd/m30")
    assert msg.index("2.12e-04") < msg.index("3.13e+00")
    assert "(not judged: within the absolute bound) 3.13e+00 at jaeger/m10000" in msg
    inside = steady.judged_message(rows[:1])
    assert inside.startswith("every cell within the 2e-5 absolute bound (judged relative error 0)")


def test_skipped_case_is_counted_and_listed_neither_pass_nor_fail(tmp_path, monkeypatch):
    """A case that cannot run here (Case.skip) is 'skipped' with its reason: not a pass, not a failure.

    The LAMMPS cases (validation/g13*) skip this way when LAMMPS cannot be imported: here the
    bridge's switch SAWDRIFT_NO_LAMMPS stands in for a missing extra.
    """
    from sawdrift.lammps.engine import load_lammps

    cases = tmp_path / "cases"
    cases.mkdir()
    (cases / "ok.py").write_text(
        "from sawdrift.validation import Case\n"
        "CASE = Case(name='ok', group='lammps', title='x', tolerance=1.0)\n"
        "def run():\n"
        "    return CASE.result(0.5)\n")
    for path in sorted((Path(__file__).resolve().parents[1] / "validation").glob("g13*.py")):
        (cases / path.name).write_text(path.read_text())
    monkeypatch.setenv("SAWDRIFT_NO_LAMMPS", "1")
    load_lammps.cache_clear()
    try:
        report = validate(tmp_path / "out", cases_dir=cases, progress=False)
    finally:
        load_lammps.cache_clear()
    skipped = {"lammps_stick_drift", "lammps_hopping", "lammps_device", "lammps_damped",
               "lammps_chains"}
    assert {r.name: r.status for r in report.results} == {"ok": "pass", **dict.fromkeys(skipped, "skipped")}
    assert report.passed and report.count("pass") == 1 and report.count("fail") == 0
    for r in report.skipped:
        assert "SAWDRIFT_NO_LAMMPS" in r.skip_reason and r.message.startswith("skipped: ")
        assert not r.expected_deviation
    assert report.summary().startswith("PASS: 1 passed, 0 failed, 0 expected deviations, 5 skipped (")
    data = json.loads((tmp_path / "out" / "results.json").read_text())
    assert data["counts"]["skipped"] == len(skipped) and data["counts"]["passed"] == 1 and data["passed"]
    assert {row["name"] for row in data["skipped"]} == skipped
    assert all("SAWDRIFT_NO_LAMMPS" in row["reason"] for row in data["skipped"])
    page = (tmp_path / "out" / "index.html").read_text()
    assert page.count(">SKIPPED<") == len(skipped) and "13. LAMMPS: the same law in a DEM engine" in page
    # a failing case next to a skipped one still fails the run
    (cases / "bad.py").write_text(
        "from sawdrift.validation import Case\n"
        "CASE = Case(name='bad', group='lammps', title='x', tolerance=1.0)\n"
        "def run():\n"
        "    return CASE.skip('never') if False else CASE.result(2.0)\n")
    monkeypatch.setenv("SAWDRIFT_NO_LAMMPS", "1")
    load_lammps.cache_clear()
    try:
        again = validate(tmp_path / "out2", cases_dir=cases, progress=False, only=["bad", "lammps_h*"])
    finally:
        load_lammps.cache_clear()
    assert {r.name: r.status for r in again.results} == {"bad": "fail", "lammps_hopping": "skipped"}
    assert not again.passed


def test_case_result_comparisons():
    le = Case(name="a", group="g", title="t", tolerance=1.0, model_tolerance={"mdr": 2.0})
    ge = Case(name="b", group="g", title="t", tolerance=4, compare=">=")
    assert le.result(1.0).passed and not le.result(1.5).passed and le.result(1.5, model="mdr").passed
    assert not le.result(float("nan")).passed and not le.result(0.0, require=False).passed
    assert ge.result(4).passed and not ge.result(3).passed
    assert isinstance(ge.result(5), CaseResult)


def test_default_cases_are_the_installed_package_resources():
    """The cases are found through the package's resources, as from an installed wheel."""
    from importlib.resources import files

    from sawdrift.validation import default_cases_dir

    found = default_cases_dir()
    assert found == Path(str(files("sawdrift.validation.cases")))
    shipped = {p.name for p in found.glob("g*.py")}
    assert len(shipped) >= 40 and "g1a_hop_threshold.py" in shipped
    # in this checkout the package is the top-level validation/ folder (pyproject maps it)
    checkout = Path(__file__).resolve().parents[1] / "validation"
    assert shipped == {p.name for p in checkout.glob("g*.py")}
    assert {lc.path.name for lc in load_cases()} == shipped


def test_the_cases_run_the_scenes_they_ship_and_those_are_the_examples():
    # three cases read examples/*.toml next to the cases: an installed wheel has no examples/,
    # and `sawdrift validate` failed there with FileNotFoundError. They ship copies in data/.
    root = Path(__file__).resolve().parents[1]
    for name in ("mixture.toml", "micro_silica_on_linbo3.toml"):
        shipped = root / "validation" / "data" / name
        assert shipped.read_bytes() == (root / "examples" / name).read_bytes(), name
    for case in root.joinpath("validation").glob("g*.py"):
        text = case.read_text()
        assert 'parents[1] / "examples"' not in text, case.name


def test_an_empty_cases_folder_is_one_line_exit_2(tmp_path, sawdrift_main):
    # it printed 'FAIL: 0 passed, 0 failed' and exited 1 with no reason
    empty = tmp_path / "empty"
    empty.mkdir()
    out = sawdrift_main("validate", "--cases", str(empty), "-o", str(tmp_path / "out"))
    err = out.stderr.strip().splitlines()
    assert out.returncode == 2 and len(err) == 1 and "holds no case files" in err[0], err


def test_a_cases_file_given_for_the_folder_is_named_a_file(tmp_path):
    """validate --cases FILE said the folder 'does not exist'."""
    afile = tmp_path / "cases.py"
    afile.write_text("")
    with pytest.raises(sd.SawdriftError, match="is a file, not a folder"):
        validate(tmp_path / "out", cases_dir=afile, progress=False)
