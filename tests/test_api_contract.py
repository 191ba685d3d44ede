"""The API contract: every operation in tests/api-contract.json is still served, unchanged."""

import json
from pathlib import Path

from fastapi.testclient import TestClient

from glasshead.api.app import create_app

CONTRACT = json.loads((Path(__file__).parent / "api-contract.json").read_text())


def test_every_contracted_operation_keeps_its_path_method_and_id():
    document = TestClient(create_app()).get("/api/v1/openapi.json").json()
    served = {(method.upper(), path): operation["operationId"]
              for path, operations in document["paths"].items()
              for method, operation in operations.items()}
    missing = [op for op in CONTRACT["operations"] if (op["method"], op["path"]) not in served]
    assert not missing, f"operations removed from the API: {missing}"
    renamed = [op for op in CONTRACT["operations"]
               if served[(op["method"], op["path"])] != op["operationId"]]
    assert not renamed, f"operation ids changed: {renamed}"


def test_operation_ids_are_unique():
    ids = [op["operationId"] for op in CONTRACT["operations"]]
    assert len(ids) == len(set(ids))
