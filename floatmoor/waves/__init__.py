"""Waves: dispersion, spectra, seeded sea realisations, Airy kinematics, excitation and
second-order wave loads (docs/theory/environment.md).
"""

from floatmoor._exports import lazy_exports

#: Public name -> the module that defines it (docs/development.md#public-api).
_API = {
    "wavenumber": "floatmoor.dispersion",
    "angular_frequency": "floatmoor.dispersion",
    "wavelength": "floatmoor.dispersion",
    "group_velocity": "floatmoor.dispersion",
    "jonswap": "floatmoor.waves.spectra",
    "pierson_moskowitz": "floatmoor.waves.spectra",
    "significant_height": "floatmoor.waves.spectra",
    "WaveField": "floatmoor.waves.realisation",
    "airy_kinematics": "floatmoor.waves.kinematics",
}
__all__, __getattr__, __dir__ = lazy_exports(__name__, _API)
