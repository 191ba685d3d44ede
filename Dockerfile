# Glasshead: one image with the API, the built assets and the web bundle.
# Build context is the repository; the reference data is mounted at /data at build and run time
# (see docker-compose.yml), never copied into the image's source tree.
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
# The server runs as an unprivileged user that owns only what it writes: the built assets, and
# var/ for the utterance cache and a SQLite database when no PostgreSQL is given.
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
EXPOSE 8000
# Build the assets from the mounted data (skipped when up to date), then serve.
CMD ["sh", "-c", "glasshead build && glasshead serve"]
