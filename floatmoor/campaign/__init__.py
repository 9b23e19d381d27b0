"""Campaigns: many runs of one case over a grid of parameter values, on local processes or
a Dask cluster, into one dataset (docs/guide/campaigns.md).
"""

from floatmoor._exports import lazy_exports

#: Public name -> the module that defines it (docs/development.md#public-api).
_API = {
    "CampaignDesign": "floatmoor.campaign.design",
    "Axis": "floatmoor.campaign.design",
    "run_campaign": "floatmoor.campaign.runner",
    "failed_runs": "floatmoor.campaign.store",
}
__all__, __getattr__, __dir__ = lazy_exports(__name__, _API)
