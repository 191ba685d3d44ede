"""Lessons: the published lesson format (``schema``) and the lessons a new store starts with
(``starter``)."""
