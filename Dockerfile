# syntax=docker/dockerfile:1
# Glasshead: one image with the API, the built assets and the web bundle; it holds no state, so
# the same image runs on any number of hosts (the state is in the database).
# Build context is the repository. The reference data is a second, named build context, "data"
# (docker-compose.yml sets it to ../shared/data): it is mounted read-only while `glasshead build`
# runs and never copied into the image, only what the build makes from it is. Alone:
#   docker build --build-context data=../shared/data -t glasshead .
FROM node:20-bookworm-slim AS web
WORKDIR /app
COPY package.json package-lock.json ./
RUN npm ci --no-audit --no-fund
COPY web ./web
RUN npx vite build web

FROM python:3.11-slim-bookworm
WORKDIR /app
RUN apt-get update && apt-get install -y --no-install-recommends espeak-ng libespeak-ng1 \
    && rm -rf /var/lib/apt/lists/*
COPY pyproject.toml README.md ./
COPY server ./server
RUN pip install --no-cache-dir '.[postgres]'
COPY --from=web /app/web/dist ./web/dist
# The server runs as an unprivileged user. It owns the built assets (written once, below) and
# var/, which only a container run without PostgreSQL writes (a SQLite database and the
# utterance cache in a directory).
RUN useradd --system --uid 10001 --home-dir /app --shell /usr/sbin/nologin glasshead \
    && mkdir -p /app/assets/build /app/var/utterances \
    && chown -R glasshead:glasshead /app/assets /app/var
USER glasshead
ENV GLASSHEAD_DATA_DIR=/data \
    GLASSHEAD_DATABASE_URL=sqlite:////app/var/glasshead.sqlite3 \
    GLASSHEAD_ASSETS_DIR=/app/assets/build \
    GLASSHEAD_SPEECH_CACHE_DIR=/app/var/utterances \
    GLASSHEAD_WEB_DIST_DIR=/app/web/dist \
    HOST=0.0.0.0 \
    PORT=8000
# The assets, built once into the image from the mounted data: every container on every host
# serves the same files, with no volume and no build at start-up.
RUN --mount=type=bind,from=data,target=/data glasshead build
EXPOSE 8000
CMD ["glasshead", "serve"]
