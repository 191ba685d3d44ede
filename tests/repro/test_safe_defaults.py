"""Safe defaults: a Content-Security-Policy and frame protection on every response, docs pages
without a CDN, a Host allow-list against DNS rebinding, no cross-site writes, a build report
without the machine's paths, and immutable caching only for content-hashed asset URLs.

Found by testing the server as an attacker: a cross-site form post imported a recording (201),
any ``?v=`` made an asset immutable for a year, and the build report named /work/... paths.
"""

import hashlib
import re

import pytest

from accounts_support import signed_in
from glasshead.api.security import allowed_host_names, inline_script_hashes
from glasshead.api.static import HASH_PREFIX
from glasshead.pipeline.report_paths import portable
from glasshead.settings import REPO_ROOT, Settings

API = "/api/v1"
ONE_FRAME = {"format": "emur-json", "content": {"frames": [{"t_ms": 0, "rows": ["00000000"] * 8}]}}


@pytest.fixture
def client(start_app):
    return signed_in(start_app()[1], "admin")


@pytest.mark.parametrize("path", [f"{API}/health", f"{API}/poses/999", "/", "/missing.js",
                                  f"{API}/openapi.json", "/assets/build/manifest.json"])
def test_every_response_carries_a_self_only_csp_nosniff_and_frame_protection(client, path):
    response = client.get(path)
    policy = response.headers["content-security-policy"]
    assert "default-src 'self'" in policy and "frame-ancestors 'none'" in policy
    assert "unsafe-inline" not in policy and "http" not in policy
    assert response.headers["x-content-type-options"] == "nosniff"
    assert response.headers["x-frame-options"] == "DENY"


@pytest.mark.parametrize("page", ["docs", "redoc"])
def test_the_docs_pages_load_every_script_and_style_from_this_server(client, page):
    response = client.get(f"{API}/{page}")
    assert response.status_code == 200
    urls = re.findall(r'(?:src|href|spec-url)="([^"]+)"', response.text)
    assert len(urls) >= 3, urls
    for url in urls:
        assert url.startswith("/"), f"{url} is not served here"
        served = client.get(url)
        assert served.status_code == 200, url
        assert b"cdn.redoc.ly" not in served.content, url  # ReDoc's footer logo, served here
    assert page != "docs" or '"validatorUrl": null' in response.text  # no validator.swagger.io
    policy = response.headers["content-security-policy"]
    assert "frame-ancestors 'none'" in policy
    scripts = re.search(r"script-src ([^;]+)", policy).group(1).split()
    assert "'unsafe-inline'" not in scripts
    assert scripts == ["'self'", *inline_script_hashes(response.text)]
    if page == "docs":  # Swagger UI starts itself with one inline script, allowed by its hash
        assert len(scripts) == 2


def test_a_docs_static_name_outside_the_package_files_is_404(client):
    assert client.get(f"{API}/docs/static/..%2F__init__.py").status_code == 404
    assert client.get(f"{API}/docs/static/core.py").status_code == 404


def test_by_default_only_loopback_names_and_the_configured_host_are_served(start_app,
                                                                          monkeypatch):
    monkeypatch.delenv("GLASSHEAD_ALLOWED_HOSTS", raising=False)
    monkeypatch.setenv("GLASSHEAD_HOST", "glasshead.school.example")
    client = start_app()[1]
    for host in ("localhost:8000", "127.0.0.1", "[::1]:8000", "glasshead.school.example"):
        assert client.get(f"{API}/health", headers={"host": host}).status_code == 200, host
    for host in ("evil.example", "evil.example:8000", "127.0.0.1.evil.example", "testserver",
                 "[::2]:8000", "not a host"):
        response = client.get(f"{API}/health", headers={"host": host})
        assert response.status_code == 400, host
        assert response.headers["content-type"] == "application/json"  # the API's error shape
        assert "GLASSHEAD_ALLOWED_HOSTS" in response.json()["detail"]
        assert "frame-ancestors 'none'" in response.headers["content-security-policy"]
    refused_write = client.post(f"{API}/epg/recordings", json=ONE_FRAME,
                                headers={"host": "evil.example", "origin": "http://evil.example"})
    assert refused_write.status_code == 400  # the host is refused first, before any route


def test_a_name_without_www_is_refused_not_redirected_to_the_allowed_www_name(start_app,
                                                                              monkeypatch):
    monkeypatch.setenv("GLASSHEAD_ALLOWED_HOSTS", "www.glasshead.example")
    client = start_app()[1]
    assert client.get(f"{API}/health", headers={"host": "www.glasshead.example"}).status_code == 200
    response = client.get(f"{API}/health", headers={"host": "glasshead.example"},
                          follow_redirects=False)
    assert response.status_code == 400 and "detail" in response.json()


def test_the_allowed_hosts_setting_replaces_the_defaults():
    names = allowed_host_names(Settings(allowed_hosts="Glasshead.District.example, lb"))
    assert names == {"glasshead.district.example", "lb"}
    assert "0.0.0.0" not in allowed_host_names(Settings(allowed_hosts="", host="0.0.0.0"))


@pytest.mark.parametrize("headers", [
    {"origin": "http://evil.example"},
    {"origin": "null"},
    {"origin": "http://testserver:8000"},  # another port is another origin
    {"sec-fetch-site": "cross-site"},
])
def test_a_cross_site_import_is_refused_with_403_and_stores_nothing(client, headers):
    response = client.post(f"{API}/epg/recordings", json=ONE_FRAME, headers=headers)
    assert response.status_code == 403, response.text
    assert "cross-site" in response.json()["detail"]
    assert client.get(f"{API}/epg/recordings").json()["total"] == 0


def test_a_cross_site_fit_or_pose_write_is_refused(client):
    evil = {"origin": "http://evil.example"}
    assert client.post(f"{API}/fits", json={}, headers=evil).status_code == 403
    assert client.post(f"{API}/poses", json={}, headers=evil).status_code == 403
    assert client.delete(f"{API}/poses/1", headers=evil).status_code == 403


@pytest.mark.parametrize("headers", [{}, {"origin": "http://testserver"},
                                     {"sec-fetch-site": "same-origin"}])
def test_a_same_origin_or_scripted_import_goes_through(client, headers):
    response = client.post(f"{API}/epg/recordings", json=ONE_FRAME, headers=headers)
    assert response.status_code == 201, response.text


def test_a_cross_site_read_is_still_served(client):
    response = client.get(f"{API}/health", headers={"origin": "http://evil.example"})
    assert response.status_code == 200


def test_only_the_files_own_hash_marks_an_asset_immutable(client, built_assets):
    name = "manifest.json"
    digest = hashlib.sha256((built_assets / name).read_bytes()).hexdigest()
    cache = {v: client.get(f"/assets/build/{name}?v={v}").headers["cache-control"]
             for v in (digest[:HASH_PREFIX], digest, digest[:HASH_PREFIX - 1], "1",
                       "0" * HASH_PREFIX)}
    assert cache == {digest[:HASH_PREFIX]: "public, max-age=31536000, immutable",
                     digest: "public, max-age=31536000, immutable",
                     digest[:HASH_PREFIX - 1]: "no-cache", "1": "no-cache",
                     "0" * HASH_PREFIX: "no-cache"}
    assert client.get(f"/assets/build/{name}").headers["cache-control"] == "no-cache"


def test_every_versioned_url_the_api_hands_out_is_served_as_immutable(client, built_assets):
    urls = [mesh["url"] for mesh in client.get(f"{API}/anatomy").json()["meshes"]]
    urls.append(client.get(f"{API}/collision/tables").json()["url"])
    observations = client.get(f"{API}/observations").json()["observations"]
    urls.append(client.get(observations[0]["url"]).json()["plot_url"])
    assert len(urls) > 10
    for url in urls:
        assert "?v=" in url, url
        response = client.get(url)
        assert response.status_code == 200, url
        assert response.headers["cache-control"].endswith("immutable"), url


def test_the_build_report_names_no_absolute_path(build_report, built_assets, data_dir):
    text = repr(build_report)
    for root in (str(built_assets.resolve()), str(data_dir.resolve()), str(REPO_ROOT)):
        assert root not in text, root
    assert build_report["tongue-rig"]["file"] == "tongue-rig.json"


def test_portable_paths_are_relative_to_the_assets_data_or_repository(tmp_path):
    report = {"a": {"file": str(tmp_path / "out" / "x.bin")},
              "b": [str(tmp_path / "data" / "anatomy" / "t.obj"), "/elsewhere/kept", 1.5],
              "c": str(REPO_ROOT / "web" / "dist"), "d": "not a path"}
    assert portable(report, assets_dir=tmp_path / "out", data_dir=tmp_path / "data") == {
        "a": {"file": "x.bin"}, "b": ["anatomy/t.obj", "/elsewhere/kept", 1.5],
        "c": "web/dist", "d": "not a path"}
