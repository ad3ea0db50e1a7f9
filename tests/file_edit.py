"""A test's edited copy of a data file: each replaced text must stand in the file exactly once,
so that an edit that no longer matches fails the test instead of silently changing nothing."""


def edited(source, target, *replacements):
    """Write ``source``'s text to ``target`` with each ``(old, new)`` of ``replacements`` made;
    returns ``target``."""
    text = source.read_text()
    for old, new in replacements:
        assert text.count(old) == 1, f"{old!r} stands {text.count(old)} times in {source}"
        text = text.replace(old, new)
    target.write_text(text)
    return target
