"""The electrodes' contact probes of an asset store's current EPG layout, made once per version
of the layout, for the routes that compute synthetic EPG."""

from glasshead.asset_store import AssetStore
from glasshead.epg.contacts import Probes, probes_from_layout


def layout_probes(store: AssetStore, grid: str = "reading62") -> Probes:
    """The probes of ``grid`` in the store's ``epg_layout``."""
    return store.derived("epg_layout", ("probes", grid),
                         lambda layout: probes_from_layout(layout["grids"][grid]))
