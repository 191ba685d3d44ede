"""What the build steps share about their own output files."""

import json
from pathlib import Path


def current_output(path, digest, builder, format_version):
    """The JSON document at ``path`` when it was built from inputs with sha256 ``digest`` by this
    ``builder`` version in this ``format_version``, so the step can skip itself; else None (also
    when the file is missing or unreadable)."""
    try:
        existing = json.loads(Path(path).read_text())
    except (OSError, json.JSONDecodeError):
        return None
    if not isinstance(existing, dict):
        return None
    source = existing.get("source")
    if isinstance(source, dict) and source.get("sha256") == digest \
            and existing.get("builder") == builder \
            and existing.get("format_version") == format_version:
        return existing
    return None
