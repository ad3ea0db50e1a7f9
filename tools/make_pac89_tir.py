"""Write the built-in example PAC89 property file from Project Chrono's HMMWV JSON.

Developer tool, run once when the source data change:

    python tools/make_pac89_tir.py tests/data/tir/HMMWV_Pac89Tire.json \
        src/tyrelab/tyre/data/hmmwv-pac89.tir

The JSON (Project Chrono, data/vehicle/hmmwv/tire/HMMWV_Pac89Tire.json,
BSD-3-Clause) holds the Pacejka '89 coefficients a0-a13, b0-b10, c0-c17 in
the ADAMS/Bakker convention, the dimensions, a linear stiffness and damping
and a load-deflection table. They are written unchanged into the ADAMS PAC89
sections [LATERAL_COEFFICIENTS], [LONGITUDINAL_COEFFICIENTS] and
[ALIGNING_COEFFICIENTS]. So that the file is a complete tyre for every
contact model, it also carries a [CONTACT_PATCH] block and a
[CONTACT_WIDTH_CURVE] that the JSON does not have: these are assumptions
(stated in the file), not measurements. No [SHAPE] table: the volume model
then uses a square section, as ADAMS does.
"""

import json
import re
import sys
from pathlib import Path


def read_json_with_comments(path):
    """Chrono's JSON files carry // comments; drop them outside strings."""
    text = Path(path).read_text()
    text = re.sub(r'("(?:\\.|[^"\\])*")|//[^\n]*', lambda m: m.group(1) or "", text)
    return json.loads(text)


def coefficient_block(section, letter, values):
    lines = [f"[{section}]"]
    for i, v in enumerate(values):
        lines.append(f"{letter}{i:<3d} = {float(v)!r}")
    return lines


def main(src, dst):
    js = read_json_with_comments(src)
    dp = js["Design Parameters"]
    lat = js["Lateral Coefficients"]
    lon = js["Longitudinal Coefficients"]
    ali = js["Aligning Coefficients"]
    r0, width = dp["Unloaded Radius"], dp["Width"]
    curve = dp["Vertical Curve Data"]
    lines = [
        "$--------------------------------------------------------------------------",
        "$ HMMWV tyre (37x12.5R16.5), Pacejka '89: built-in example PAC89 tyre of tyrelab.",
        f"$ Source: Project Chrono, data/vehicle/hmmwv/tire/{Path(src).name} (BSD-3-Clause),",
        "$ written by tools/make_pac89_tir.py. Coefficients in the ADAMS/Bakker convention",
        "$ (Fz in kN, slip angle and camber in degrees, longitudinal slip in percent).",
        f"$ The source states a friction coefficient of {js.get('Coefficient of Friction', 'n/a')}",
        "$ for the road the coefficients were measured on, a lateral stiffness of",
        f"$ {dp.get('Lateral Stiffness', 'n/a')} N/m and a rolling resistance coefficient of",
        f"$ {dp.get('Rolling Resistance', 'n/a')} (not used by tyrelab's PAC89).",
        "$--------------------------------------------------------------------------",
        "[MDI_HEADER]",
        "FILE_TYPE     = 'tir'",
        "FILE_VERSION  = 3.0",
        "FILE_FORMAT   = 'ASCII'",
        "[UNITS]",
        "LENGTH = 'meter'",
        "FORCE  = 'newton'",
        "ANGLE  = 'radians'",
        "MASS   = 'kg'",
        "TIME   = 'second'",
        "[MODEL]",
        "PROPERTY_FILE_FORMAT = 'PAC89'",
        "TYRESIDE             = 'LEFT'",
        "[DIMENSION]",
        f"UNLOADED_RADIUS = {r0!r}",
        f"WIDTH           = {width!r}",
        "[INERTIA]",
        f"MASS = {js['Mass']!r}   $ tyre",
        f"IYY  = {js['Inertia'][1]!r}   $ tyre spin inertia, kg m^2",
        "[VERTICAL]",
        f"VERTICAL_STIFFNESS = {dp['Vertical Stiffness']!r}   $ used only with linear stiffness",
        f"VERTICAL_DAMPING   = {dp['Vertical Damping']!r}",
        "[DEFLECTION_LOAD_CURVE]",
        "{pen fz}",
    ]
    lines += [f"{d!r} {f!r}" for d, f in curve]
    lines += [
        "$---------------------------------------------- 3D enveloping contact: ASSUMED",
        "$ The source has no contact-patch data. Length and cam shape are the thesis's",
        "$ dimensionless XZL values (section 4.4); cam counts are Schmeitz's passenger-car",
        "$ optimum (5 along, 6 across); the half contact width comes from the table below",
        "$ (0.8 of the half section width), because the PB1-PB3 formula needs a fit.",
        "[CONTACT_PATCH]",
        "PA1      = 0.15",
        "PA2      = 7.06",
        "PAE      = 0.72",
        "PBE      = 1.0",
        "PCE      = 2.0",
        "PLS      = 0.9",
        "N_WIDTH  = 6",
        "N_LENGTH = 5",
        "[CONTACT_WIDTH_CURVE]",
        "{deflection half_width}",
        f"0.0 {0.4 * width!r}",
        f"0.1 {0.4 * width!r}",
        "$---------------------------------------------- Pacejka '89 coefficients",
    ]
    lines += coefficient_block("LATERAL_COEFFICIENTS", "A", [lat[f"a{i}"] for i in range(14)])
    lines += coefficient_block("LONGITUDINAL_COEFFICIENTS", "B", [lon[f"b{i}"] for i in range(11)])
    lines += coefficient_block("ALIGNING_COEFFICIENTS", "C", [ali[f"c{i}"] for i in range(18)])
    Path(dst).write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
