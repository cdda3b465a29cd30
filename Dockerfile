# knotshape container image: a multi-stage build. The builder compiles the
# release binary with the committed Cargo.lock (--locked); the runtime image is
# distroless (glibc + libgcc, no shell, no package manager) running as a
# numeric non-root user. Needs a builder that knows `RUN --mount=type=cache`:
# BuildKit (Docker 23 or newer, its default) or Podman/Buildah.
#   docker build -t knotshape .
#   docker run --rm -p 8080:8080 --read-only knotshape
# (`podman build` / `podman run` take the same arguments.)
#
# The two base images are build arguments, so that a site that mirrors images
# can build it, e.g.
#   docker build -t knotshape
#     --build-arg RUST_IMAGE=mirror.example/library/rust:1.95-slim-bookworm
#     --build-arg RUNTIME_IMAGE=mirror.example/distroless/cc-debian12:nonroot .
# (one command, written over three lines).
# Keep the pair matched: the runtime must have the glibc the builder linked
# against (Debian 12 "bookworm" for both). The names are fully qualified, so
# Podman needs no short-name resolution.

ARG RUST_IMAGE=docker.io/library/rust:1.95-slim-bookworm
ARG RUNTIME_IMAGE=gcr.io/distroless/cc-debian12:nonroot

# ---------------------------------------------------------------- builder ---
FROM ${RUST_IMAGE} AS builder
WORKDIR /src

# The whole context (filtered by .dockerignore) is copied: a dummy-main
# "dependencies first" layer breaks as soon as Cargo.toml names explicit
# targets, so dependency reuse comes from cache mounts instead: the registry
# and the target directory survive between builds, and only crates whose
# inputs changed are recompiled. The binary is copied out of the cache mount
# in the same step, because the mount is not part of the image.
# The slim image has gcc, which the mimalloc allocator's C source needs.
COPY . .
RUN --mount=type=cache,target=/usr/local/cargo/registry,sharing=locked \
    --mount=type=cache,target=/usr/local/cargo/git,sharing=locked \
    --mount=type=cache,target=/src/target,sharing=locked \
    cargo build --release --locked --bin knotshape \
    && install -D -m 0755 target/release/knotshape /out/knotshape

# ---------------------------------------------------------------- runtime ---
# Bookworm builder + debian12 runtime: the same glibc the binary was linked
# against. The :nonroot tag already defines uid/gid 65532; it is repeated below
# as a number so that Kubernetes' runAsNonRoot can verify it without
# resolving a user name.
FROM ${RUNTIME_IMAGE} AS runtime

LABEL org.opencontainers.image.title="knotshape" \
      org.opencontainers.image.description="HTTP microservice that evaluates B-spline/NURBS curves and edits their shape by moving knot pairs" \
      org.opencontainers.image.licenses="MIT OR Apache-2.0"

COPY --from=builder /out/knotshape /usr/local/bin/knotshape

# Inside a container the service must accept connections from outside its
# network namespace; the binary's own default is loopback only.
ENV KNOTSHAPE_LISTEN=0.0.0.0:8080 \
    KNOTSHAPE_LOG_FORMAT=json
EXPOSE 8080

USER 65532:65532

# No shell, curl or wget in the image: the binary probes its own /healthz at
# the configured listen address and exits 0 (healthy) or 1.
HEALTHCHECK --interval=10s --timeout=3s --start-period=5s --retries=3 \
    CMD ["/usr/local/bin/knotshape", "healthcheck"]

# SIGTERM starts the graceful drain (readiness turns 503, in-flight requests
# finish). Exec form: the binary is PID 1 and receives the signal directly.
STOPSIGNAL SIGTERM
ENTRYPOINT ["/usr/local/bin/knotshape"]
