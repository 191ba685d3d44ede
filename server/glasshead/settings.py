"""Settings read from the environment; the defaults work out of the box from a clone."""

import os
from functools import lru_cache
from pathlib import Path
from typing import Literal

from pydantic import AliasChoices, Field
from pydantic_settings import BaseSettings, SettingsConfigDict

#: The repository root (server/glasshead/settings.py -> ../../..).
REPO_ROOT = Path(__file__).resolve().parents[2]


class Settings(BaseSettings):
    """Glasshead settings. Each field may be set by the environment variable named beside it."""

    model_config = SettingsConfigDict(env_prefix="GLASSHEAD_", extra="ignore")

    host: str = Field("127.0.0.1", validation_alias=AliasChoices("HOST", "GLASSHEAD_HOST"))
    port: int = Field(8000, ge=1, le=65535, validation_alias=AliasChoices("PORT", "GLASSHEAD_PORT"))
    #: Host names the server answers to, comma-separated (DNS rebinding guard); empty: the
    #: loopback names and ``host``. Behind a load balancer: the name users type.
    allowed_hosts: str = ""
    #: The address children's tablets and the school's computers reach this server at
    #: (``http://glasshead.school.example:8000``), for the join link and its QR code a teacher
    #: shows; empty: the address the teacher's own browser used.
    public_url: str = Field("", pattern=r"^(https?://[^\s/?#]+(/[^\s?#]*)?)?$")
    #: Reference data (meshes, EPG, ultrasound); read-only.
    data_dir: Path = REPO_ROOT.parent / "shared" / "data"
    #: Output of `glasshead build`.
    assets_dir: Path = REPO_ROOT / "assets" / "build"
    #: The built web app (`vite build web`).
    web_dist_dir: Path = REPO_ROOT / "web" / "dist"
    #: Utterances made by POST /utterances (JSON and WAV, named by content hash); disposable.
    #: Used when the utterance cache is a directory (see ``utterance_cache``).
    speech_cache_dir: Path = REPO_ROOT / "assets" / "build" / "utterances"
    #: SQLAlchemy URL; SQLite by default, PostgreSQL in docker-compose.
    database_url: str = f"sqlite:///{REPO_ROOT / 'var' / 'glasshead.sqlite3'}"
    #: Where utterances are cached: ``directory`` (``speech_cache_dir``, this machine's disk),
    #: ``database`` (a table, shared by every server on the database) or ``auto``: the database
    #: on PostgreSQL, the directory on SQLite.
    utterance_cache: Literal["auto", "directory", "database"] = "auto"
    #: Worker processes that run fit jobs (POST /fits; 0: this server runs none, others on the
    #: same database do), and how many jobs may wait for them.
    fit_workers: int = Field(1, ge=0, le=64)
    fit_queue_limit: int = Field(8, ge=1, le=10000)
    #: Worker processes for the CPU-heavy routes (default: the CPU count), and how many
    #: requests may wait for them before the server answers 503 (glasshead.jobs.compute).
    compute_workers: int = Field(default_factory=lambda: os.cpu_count() or 1, ge=1, le=256)
    compute_queue_limit: int = Field(32, ge=0, le=10000)

    @property
    def on_postgres(self) -> bool:
        return self.database_url.startswith(("postgresql:", "postgresql+", "postgres:"))

    @property
    def utterance_cache_kind(self) -> Literal["directory", "database"]:
        """``utterance_cache`` with ``auto`` decided."""
        if self.utterance_cache == "auto":
            return "database" if self.on_postgres else "directory"
        return self.utterance_cache


@lru_cache
def get_settings() -> Settings:
    """The process-wide settings (cached; tests clear the cache after changing the environment)."""
    return Settings()
