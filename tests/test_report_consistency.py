"""The report's consistency with what the thesis measured, on a real study rendered in Chromium.

A small real study (``tyrelab.study.run``, one worker process) drives two of the thesis's
variants, OPC lk and 3D VC lk, over the 50 mm cleat at 12 km/h, LC1 -- the condition of
the thesis's Table 5-2 -- against a reference model *labelled* "FTire TP": the consistency
part is shown for a reference of that label (what it stands for is the study's business;
here the enveloping model keeps the test cheap). The counts on the page are checked
against the bound worked from Table 5-2, typed here, and the study's own metrics.
"""

from __future__ import annotations

import pytest

from chromium import INSTALL_HINT, find_chromium, parse, render_dom
from tyrelab.report.study_report import write_study_report

#: Table 5-2 (50 mm cleat, 12 km/h, LC1): m%RE, 80%RE, RMS of the disturbance, m%RE,
#: RMS of the response, typed from the thesis
T52 = {"FTire TP": (6, 10, 752, 10, 2256), "OPC lk": (37, 53, 4624, 35, 8410),
       "3D VC lk": (7, 11, 1050, 34, 9279)}
COUNTED = ("mRE_disturbance_pct", "rms_disturbance_N", "mRE_response_pct", "rms_response_N")
ALL = ("mRE_disturbance_pct", "RE80_disturbance_pct", "rms_disturbance_N", "mRE_response_pct",
       "rms_response_N")
SPEC = """\
[study]
name = "consistency-report"
output = "out"

[[tyre]]
name = "xzl"
file = "xzl-16.00R20"

[[model]]
name = "OPC lk"
contact = "point"
stiffness = "linear"

[[model]]
name = "3D VC lk"
contact = "volume"
stiffness = "linear"

[[model]]
name = "FTire TP"
contact = "enveloping"
stiffness = "table"

[[test]]
name = "cleat 50x50 perpendicular"
road = "cleat:50x50"
speeds_kmh = [12]
loads = ["LC1"]
duration = 3.0
reference = { model = "FTire TP" }
"""


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    from tyrelab import study as studies
    folder = tmp_path_factory.mktemp("consistency")
    (folder / "spec.toml").write_text(SPEC)
    return studies.run(folder / "spec.toml", workers=1, progress=False)


def by_hand(study) -> tuple[int, int]:
    """Cells within the bound over the counted metrics, from T52 and the study's metrics."""
    m = study.metrics
    within = cells = 0
    for model in ("OPC lk", "3D VC lk"):
        row = m[(m["model"] == model) & ~m["is_reference"]].iloc[0]
        for i, metric in enumerate(ALL):
            if metric in COUNTED:
                cells += 1
                within += abs(row[metric]) <= T52[model][i] + T52["FTire TP"][i]
    return within, cells


def test_the_consistency_section_renders_with_the_counts_worked_by_hand(study, tmp_path):
    if find_chromium() is None:
        pytest.fail("Chromium is needed to check the study report renders: " + INSTALL_HINT)
    within, cells = by_hand(study)
    assert cells == 8
    path = write_study_report(study, tmp_path / "report.html")
    dom = parse(render_dom(path))
    errors = dom.find("pre", id="tyrelab-errors")
    assert errors is not None and errors.text().strip() == "", errors and errors.text()
    total = dom.find("p", cls="consistency-total")
    assert total is not None and total.attrs["data-view"] == "ours"
    assert f"{within} of {cells}" in " ".join(total.text().split())
    # Table 5-15: one row (cleats) x the two columns the study ran, OPC and 3D VC
    rows = dom.find("table", cls="consistency-5-15").find_all("tr")[1:]
    assert len(rows) == 2
    # the folded list holds every cell: 2 models x 5 metrics
    assert len(dom.find("table", cls="consistency-cells").find_all("tr")) == 1 + 2 * 5


def test_no_consistency_section_without_an_ftire_tp_reference(study, tmp_path):
    """The same study's reference relabelled is no thesis stand-in: no section."""
    from tyrelab.study.results import Study
    relabelled = Study(study.folder)
    relabelled.__dict__["metrics"] = study.metrics.replace({"model": {"FTire TP": "ENV ref"}})
    assert relabelled.consistency is None
    text = (write_study_report(relabelled, tmp_path / "r.html")).read_text(encoding="utf-8")
    assert "consistency-total" not in text
