"""The posed tract's shape made from an asset store's current assets, for POST
/tract/acoustics (``speech.tract_shape``)."""

from glasshead.asset_store import AssetStore
from glasshead.flesh_point_assets import FLESH_POINT_ASSETS, flesh_point_rig
from glasshead.speech.tract_shape import TractShape

#: The assets the tract's shape reads besides the flesh points' ones.
TRACT_ASSETS = ("velum_rig", "velum_mesh", "tract_section")


def tract_shape(store: AssetStore) -> TractShape:
    """The tract's shape of the store's current assets, prepared once per version of them."""
    entries = {name: store.entry(name) for name in FLESH_POINT_ASSETS + TRACT_ASSETS}
    key = ("tract_shape",) + tuple(e.sha256 for e in entries.values())
    flesh = flesh_point_rig(store)  # not inside derived(): it holds the store's lock
    return store.derived("tract_section", key, lambda section: TractShape(
        flesh, entries["velum_rig"].value, entries["velum_mesh"].value[1],
        {"upper_lip": entries["upper_lip_mesh"].value[1],
         "lower_lip": entries["lower_lip_mesh"].value[1]},
        section))
