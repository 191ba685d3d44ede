"""The flesh points' rig made from an asset store's current assets, for the API's utterances
and for the comparison with real articulography (``speech.ema_comparison``)."""

from glasshead.asset_store import AssetStore
from glasshead.geometry.flesh_points import FleshPointRig

#: The assets the flesh points read (besides the phoneme targets, all of them part of the cache
#: key of an utterance that asks for them).
FLESH_POINT_ASSETS = ("tongue_rig", "face_rig", "landmarks", "upper_lip_mesh", "lower_lip_mesh")


def flesh_point_rig(store: AssetStore) -> FleshPointRig:
    """The flesh points' rig of the store's current assets, prepared once per version of them."""
    entries = {name: store.entry(name) for name in FLESH_POINT_ASSETS}
    key = ("flesh_points",) + tuple(e.sha256 for e in entries.values())
    return store.derived("face_rig", key, lambda face: FleshPointRig(
        entries["tongue_rig"].value, face,
        {"upper_lip": entries["upper_lip_mesh"].value[0],
         "lower_lip": entries["lower_lip_mesh"].value[0]},
        entries["landmarks"].value))
