"""Argument parsing helpers for the command line (units converted here, once)."""

from __future__ import annotations

import argparse
import math

from ..errors import InputError


def positive_float(name: str, scale: float = 1.0):
    """argparse type: a positive finite number, multiplied by ``scale`` into SI."""
    def parse(text: str) -> float:
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} must be a number, got '{text}'") from None
        if not (math.isfinite(value) and value > 0):
            raise argparse.ArgumentTypeError(f"{name} must be a positive number, got '{text}'")
        return value * scale
    parse.__name__ = name
    return parse


def load_value(text: str):
    """A load case name (LC1..LC3) or a wheel load in N."""
    try:
        value = float(text)
    except ValueError:
        return text
    if not (math.isfinite(value) and value > 0):
        raise argparse.ArgumentTypeError(f"load must be a load case (LC1-LC3) or a positive force in N, "
                                         f"got '{text}'")
    return value


def output_path(text: str) -> str:
    if not (text.lower().endswith(".parquet") or text.lower().endswith(".csv")):
        raise InputError(f"output file '{text}' must end in .parquet or .csv", field="-o")
    return text
