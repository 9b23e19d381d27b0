"""Post-processing of a result dataset's channels: statistics, extremes, spectra, rainflow,
fatigue, strength, the run summary and the comparison with measured cycles.
"""

from floatmoor._exports import lazy_exports

#: Public name -> the module that defines it (docs/development.md#public-api).
_API = {
    "channel_statistics": "floatmoor.post.statistics",
    "time_statistics": "floatmoor.post.statistics",
    "extrema": "floatmoor.post.extremes",
    "exceedance_probability": "floatmoor.post.extremes",
    "welch_psd": "floatmoor.post.spectra",
    "spectral_moments": "floatmoor.post.spectra",
    "rainflow_cycles": "floatmoor.post.rainflow",
    "SNCurve": "floatmoor.post.fatigue",
    "TNCurve": "floatmoor.post.fatigue",
    "fatigue_damage": "floatmoor.post.fatigue",
    "damage_equivalent_load": "floatmoor.post.fatigue",
    "line_strength": "floatmoor.post.run_strength",
    "safety_factor": "floatmoor.post.run_strength",
    "tension_envelope": "floatmoor.post.line_shapes",
    "run_summary": "floatmoor.post.summary",
    "read_measured_cycle": "floatmoor.post.comparison",
    "align_cycles": "floatmoor.post.comparison",
}
__all__, __getattr__, __dir__ = lazy_exports(__name__, _API)
