# The gRPC balancer of docker/docker-compose.replicas.yml: Debian 12's HAProxy with
# docker/haproxy.cfg (addresses from the environment: ORBIT_BALANCER_LISTEN, ORBIT_REPLICA_1..3).
#   docker build -f docker/balancer.Dockerfile -t orbit-balancer docker
FROM debian:12-slim
RUN apt-get update \
 && apt-get install -y --no-install-recommends haproxy \
 && apt-get clean \
 && rm -rf /var/lib/apt/lists/*
COPY haproxy.cfg /etc/haproxy/orbit.cfg
USER haproxy
EXPOSE 50051
# -db: stay in the foreground, log to stderr (the container's log).
ENTRYPOINT ["haproxy", "-f", "/etc/haproxy/orbit.cfg", "-db"]
