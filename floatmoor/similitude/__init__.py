"""Dynamic similitude of mooring cases (docs/theory/similitude.md;
chain-experiment paper section 2).

:func:`~floatmoor.similitude.groups.cable_groups` gives the dimensionless groups of every line
of a case (alpha_1 to alpha_5, Reynolds and Keulegan-Carpenter numbers);
:class:`~floatmoor.similitude.laws.ScaleLaw` the scale factors of a law;
:func:`~floatmoor.similitude.case_scaling.scale_case_file` writes a scaled case.
"""

from floatmoor.similitude.groups import cable_groups
from floatmoor.similitude.laws import ScaleLaw

__all__ = ["cable_groups", "ScaleLaw"]
