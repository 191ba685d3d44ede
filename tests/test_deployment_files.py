"""The deployment files say what the docs say: the image runs as an unprivileged user with the
assets built into it, and docker-compose.yml runs PostgreSQL and several health-checked app
containers behind a load balancer, which keep nothing on a host's disk (their state, the fit
queue and the utterance cache are in PostgreSQL). There is no container engine here, so the
files are parsed and read."""

import re
from pathlib import Path

import yaml

REPO = Path(__file__).resolve().parents[1]


def compose() -> dict:
    return yaml.safe_load((REPO / "docker-compose.yml").read_text())


def test_the_image_runs_as_a_user_that_is_not_root():
    final_stage = (REPO / "Dockerfile").read_text().split("\nFROM ")[-1]
    users = re.findall(r"^USER\s+(\S+)", final_stage, flags=re.MULTILINE)
    assert users and users[-1] not in ("root", "0", "0:0")
    assert final_stage.index("USER") < final_stage.index("CMD")


def test_compose_runs_postgres_with_a_health_check_and_a_volume():
    db = compose()["services"]["db"]
    assert db["image"].startswith("postgres:")
    assert "pg_isready" in " ".join(db["healthcheck"]["test"])
    assert any(volume.endswith(":/var/lib/postgresql/data") for volume in db["volumes"])


def test_compose_runs_several_health_checked_app_containers_on_postgres():
    services = compose()["services"]
    app = services["app"]
    assert app["deploy"]["replicas"] >= 2
    assert "--workers" in app["command"]
    assert app["depends_on"]["db"]["condition"] == "service_healthy"
    environment = app["environment"]
    assert environment["GLASSHEAD_DATABASE_URL"].startswith("postgresql+psycopg://")
    assert "@db:5432/" in environment["GLASSHEAD_DATABASE_URL"]
    # the health check asks 127.0.0.1, which the host allow-list must let through
    assert "127.0.0.1" in " ".join(app["healthcheck"]["test"])
    assert "127.0.0.1" in environment["GLASSHEAD_ALLOWED_HOSTS"].split(",")


def test_the_app_containers_keep_nothing_on_a_hosts_disk():
    """So that they can run on several hosts: no volume, a read-only file system (scratch
    files in memory), the utterance cache in the database, and the only named volume the
    database's own."""
    document = compose()
    app = document["services"]["app"]
    assert "volumes" not in app
    assert app["read_only"] is True and "/tmp" in app["tmpfs"]
    assert app["environment"]["GLASSHEAD_UTTERANCE_CACHE"] == "database"
    assert set(document["volumes"]) == {"db-data"}
    assert set(document["services"]) == {"db", "app", "lb"}


def test_the_assets_are_built_into_the_image_from_data_mounted_at_build_time():
    build = compose()["services"]["app"]["build"]
    assert build["additional_contexts"]["data"] == "../shared/data"
    dockerfile = (REPO / "Dockerfile").read_text()
    assert dockerfile.startswith("# syntax=docker/dockerfile:1")
    final_stage = dockerfile.split("\nFROM ")[-1]
    built = re.search(r"^RUN --mount=type=bind,from=data,target=(\S+) glasshead build$",
                      final_stage, flags=re.MULTILINE)
    assert built is not None
    data_dir = re.search(r"GLASSHEAD_DATA_DIR=(\S+)", final_stage).group(1)
    assert built.group(1) == data_dir  # the build reads the data where the settings say
    assert not re.search(r"^(COPY|ADD) .*(--from=data|shared)", dockerfile, flags=re.MULTILINE)
    assert final_stage.index("USER") < final_stage.index("glasshead build")  # owned by the user


def test_compose_puts_a_load_balancer_in_front_of_every_app_container():
    document = compose()
    lb = document["services"]["lb"]
    assert any(port.endswith(":80") for port in lb["ports"])
    config_mount = next(v for v in lb["volumes"] if "nginx.conf" in v)
    config = (REPO / config_mount.split(":")[0]).read_text()
    assert "http://app:8000" in config and "proxy_set_header Host $http_host" in config
    used = {volume.split(":")[0] for service in document["services"].values()
            for volume in service.get("volumes", []) if not volume.startswith(".")}
    assert used <= set(document["volumes"])
