"""``[campaign]``: the sweep of a case that ``floatmoor sweep`` runs, declared and read.

``[campaign.grid]`` and ``[campaign.zip]`` map quoted key paths of the case to arrays of
values, e.g. ``"motion.period" = [1.25, 3.5]``; the keys and values are checked when the
campaign's runs are (:mod:`floatmoor.campaign.design`), not here.
"""

from __future__ import annotations

from typing import Any

from floatmoor.case.reader import MISSING, TableReader
from floatmoor.case.setting import Setting, SettingTable

__all__ = ["read_campaign", "CAMPAIGN_TABLES"]

#: The one key of the case's top level declared here.
_TOP = SettingTable("", {
    "campaign": Setting("table", doc="A sweep of the case over several values of its keys, "
                        "run by `floatmoor sweep`: every combination of `[campaign.grid]`, "
                        "element-wise with `[campaign.zip]`."),
})
_CAMPAIGN = SettingTable("campaign", {
    "grid": Setting("table", default={}, doc="Keys whose value arrays are combined, every "
                    "value with every other (a full grid)."),
    "zip": Setting("table", default={}, doc="Keys whose value arrays, of one length, are "
                   "taken element by element."),
})
#: The swept keys of each kind of sweep (any key path of the case, hence ``<key>``).
_SWEPT = {
    "grid": SettingTable("campaign.grid", {
        "<key>": Setting("array", doc="A quoted key path of the case (`\"motion.period\"`) "
                         "and the array of values to sweep; checked when the runs are."),
    }),
    "zip": SettingTable("campaign.zip", {
        "<key>": Setting("array", doc="A quoted key path of the case and the array of values "
                         "to sweep, as long as the other `[campaign.zip]` arrays."),
    }),
}
#: Every declared table of ``[campaign]`` (for the reference's tests).
CAMPAIGN_TABLES = (_TOP, _CAMPAIGN, *_SWEPT.values())


def read_campaign(root: TableReader) -> dict[str, dict[str, list[Any]]]:
    """The ``[campaign]`` table of the case's top level ``root``: ``{"grid": {key: values},
    "zip": {key: values}}``, at least one swept key."""
    t = _TOP.table(root, "campaign")
    out: dict[str, dict[str, list[Any]]] = {}
    for kind in ("grid", "zip"):
        table = _CAMPAIGN.table(t, kind)
        for key in list(table.data):
            values = _SWEPT[kind].read(table, key, declared="<key>")
            if not isinstance(values, list) or not values:
                raise table.error(key, "a non-empty array of values to sweep", values)
        out[kind] = dict(table.data)
        table.finish()
    if not out["grid"] and not out["zip"]:
        raise t.error("grid", "at least one swept key in [campaign.grid] or [campaign.zip]",
                      MISSING)
    t.finish()
    return out
