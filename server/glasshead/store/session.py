"""The one database dependency of the API: ``SessionDep``, a session per request.

Routes commit what they change; a request that fails before its commit leaves nothing behind,
because the session rolls back when it closes.
"""

from collections.abc import Iterator
from functools import lru_cache
from typing import Annotated

from fastapi import Depends
from sqlalchemy import Engine
from sqlalchemy.orm import Session, sessionmaker

from glasshead.store.db import get_engine


@lru_cache(maxsize=8)
def _sessions_for(engine: Engine) -> sessionmaker[Session]:
    return sessionmaker(bind=engine, expire_on_commit=False)


def get_session() -> Iterator[Session]:
    with _sessions_for(get_engine())() as session:
        yield session


SessionDep = Annotated[Session, Depends(get_session)]
