"""GET /site: the address children's tablets reach the server at, for a class's join link."""

import pytest
from pydantic import ValidationError

from glasshead.settings import Settings

API = "/api/v1"


def test_without_a_public_url_the_site_says_none_so_the_page_uses_its_own(start_app):
    _, client = start_app()
    assert client.get(f"{API}/site").json() == {"public_url": None}


def test_the_public_url_is_given_without_its_trailing_slash_to_anyone(start_app, monkeypatch):
    monkeypatch.setenv("GLASSHEAD_PUBLIC_URL", "http://glasshead.school.example:8000/")
    _, client = start_app()
    response = client.get(f"{API}/site")
    assert response.status_code == 200
    assert response.json() == {"public_url": "http://glasshead.school.example:8000"}


@pytest.mark.parametrize("url", ["glasshead.school.example", "ftp://school.example",
                                 "http://school example", "http://school.example/?q=1"])
def test_a_public_url_that_is_no_web_address_stops_the_server_at_start(url):
    with pytest.raises(ValidationError, match="public_url"):
        Settings(public_url=url)
