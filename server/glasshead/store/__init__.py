"""The application's database: SQLAlchemy 2 models, Alembic migrations and the API session.

``base`` declares the model base (naming conventions, UTC timestamps); ``models`` the tables;
``db`` the engine (from ``GLASSHEAD_DATABASE_URL``; a SQLite file under ``var/`` by default) and
the upgrade to the newest migration, run at application start-up; ``session`` the one
``SessionDep`` dependency for routes. Migrations live in ``migrations/versions``; every schema
change is a new revision there, so SQLite and PostgreSQL stores upgrade the same way.
"""
