"""A small study spec as text, for tests that need a study around one tyre (test helper)."""

from __future__ import annotations


def study_spec(tyre_lines: str, models=(("A", "point"),), reference: str | None = None) -> str:
    """The TOML of a study named "t": one ``[[tyre]]`` of ``tyre_lines``, a ``[[model]]`` per
    ``(name, contact)`` and a 20 mm cleat test at 12 km/h and 5 kN (1 s), compared with the
    model ``reference`` if given. Its first ``[[model]]``'s ``contact`` stands on line
    ``8 + tyre_lines' line count``, each further model's 4 lines below."""
    text = f'[study]\nname = "t"\n\n[[tyre]]\n{tyre_lines}\n'
    for name, contact in models:
        text += f'\n[[model]]\nname = "{name}"\ncontact = "{contact}"\n'
    text += ('\n[[test]]\nname = "cleat"\nroad = "cleat:20x20"\nspeeds_kmh = [12]\nloads = [5000]\n'
             'duration = 1.0\n')
    if reference is not None:
        text += f'reference = {{ model = "{reference}" }}\n'
    return text
