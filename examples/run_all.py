"""Run every example into one folder; with ``--figures DIR`` also copy their PNG figures there.

``python examples/run_all.py OUT --figures docs/examples/img`` refreshes the
figures the documentation shows (each example page shows its script's output).
``tests/test_examples.py`` runs the same scripts one by one and checks what
they print.
"""

import argparse
import shutil
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
#: the gallery, in the documentation's order: script -> the figures it writes
EXAMPLES = {
    "cleat_run.py": ["cleat_run.png"],
    "model_comparison.py": ["model_comparison.png"],
    "roads.py": ["roads_crg.png", "roads_profiles.png"],
    "fit_tyre.py": ["fit_tyre.png"],
    "small_campaign.py": ["small_campaign.png"],
}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", type=Path, help="folder the examples write into")
    parser.add_argument("--figures", type=Path, default=None, help="also copy the figures here")
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    for script, figures in EXAMPLES.items():
        print(f"== {script}", flush=True)
        subprocess.run([sys.executable, str(HERE / script), str(args.out)], check=True)
        if args.figures:
            args.figures.mkdir(parents=True, exist_ok=True)
            for fig in figures:
                shutil.copyfile(args.out / fig, args.figures / fig)
    return 0


if __name__ == "__main__":
    sys.exit(main())
