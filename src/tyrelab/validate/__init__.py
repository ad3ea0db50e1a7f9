"""Validation of simulated runs against measurements (thesis chapter 5 and more)."""

from .align import Aligned, align, estimate_shift
from .compare import (METRICS, THESIS_CLEAT, THESIS_TRACK, beside_repeatability,
                      compare_aligned, compare_runs, metric_row, repeatability)
from .comprehensive import russell, sprague_geers
from .distributions import fit_normal, histogram_density, normal_fit_errors, normality
from .fatigue import cycles, equivalent_range, extremes, peak_load_errors, pseudo_damage
from .metrics import (disturbance_errors, match_peaks, mean_relative_error, percent_error,
                      relative_error, relative_error_percentile, response_peak_errors,
                      rms_error)
from .segments import (Segments, segments_from_geometry, segments_from_signal,
                       segments_from_speed)
from .spectra import band_rms, compare_psd, psd
from .tables import (metrics_table, rank_models, summary_html, summary_markdown,
                     table_markdown_by_metric,
                     summary_table, table_html, table_markdown)

__all__ = [n for n in dir() if not n.startswith("_")]
