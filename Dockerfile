# fresnel in a container (Debian 12), for batch rendering on clusters (docs/batch.md).
# The packages are scripts/packages.txt, installed by scripts/install-deps.sh, as `make demo`
# does; ffmpeg is added for `render --video`. Renders headless on Mesa's llvmpipe (EGL); no GPU
# or display needed.
#   docker build -t fresnel .
#   docker run --rm -v "$PWD:/data" fresnel render /data/model.glb -o /data/out.png
FROM debian:12
ENV DEBIAN_FRONTEND=noninteractive
WORKDIR /src
COPY scripts/packages.txt scripts/install-deps.sh scripts/
RUN scripts/install-deps.sh \
 && apt-get install -y -qq --no-install-recommends ffmpeg \
 && rm -rf /var/lib/apt/lists/*
COPY . .
RUN cmake -S . -B /build -G Ninja -DCMAKE_BUILD_TYPE=Release -DFRESNEL_TESTS=OFF -DFRESNEL_BENCH=OFF \
 && cmake --build /build --target fresnel \
 && install -m 755 /build/bin/fresnel /usr/local/bin/fresnel \
 && rm -rf /build \
 && fresnel render -o /tmp/smoke.png --size 64x48 --no-cache && rm /tmp/smoke.png
# Caches (baked environments, Mesa's shader cache) go to a writable place; mount a volume here
# to keep them between containers.
ENV XDG_CACHE_HOME=/cache
RUN mkdir -p /cache && chmod 1777 /cache
WORKDIR /data
ENTRYPOINT ["fresnel"]
CMD ["--help"]
