"""Write src/tyrelab/tyre/handling/mf/coefficient_index.py from the Magic Formula's name list.

    python tools/make_mf_coefficient_index.py

Run it after any change to ``PARAMETERS`` or ``DERIVED`` in
``tyrelab/tyre/handling/mf/coefficients.py``; ``tests/test_mf_coefficient_index.py``
fails until the generated module is current.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

MODULE = (Path(__file__).resolve().parents[1] / "src" / "tyrelab" / "tyre" / "handling" / "mf"
          / "coefficient_index.py")


def main() -> None:
    if not MODULE.exists():  # the package's kernels import it: give them an empty one to start from
        MODULE.write_text("")
    spec = importlib.util.find_spec("tyrelab.tyre.handling.mf.coefficients")
    if spec is None or Path(spec.origin).resolve().parent != MODULE.parent:
        raise SystemExit(f"tyrelab is not imported from this checkout ({spec and spec.origin})")
    from tyrelab.tyre.handling.mf.coefficients import NAMES, index_module_source
    text = index_module_source()
    if MODULE.read_text() == text:
        print(f"{MODULE.name} is current")
        return
    MODULE.write_text(text)
    print(f"wrote {MODULE} ({len(NAMES)} coefficients)")


if __name__ == "__main__":
    main()
