#!/usr/bin/env python3
"""Orbit's API from a second language: a Python client on Debian's python3-grpcio.

Starts a real `orbit serve` on a free loopback port with a fresh SQLite file, enrolls two
COIL-100 objects with the C++ command line (`orbit enroll`), then, from Python only, asks the
server what it holds and streams a recognition session over object 2 - half the frames as
descriptors in the server's variant (from `orbit descriptor`), half as encoded PNG images for the server to
describe - and checks that every frame got exactly one update, in order, and that object 2 ends
on top. Exit status 0 on success; each failed check is printed.

Usage: session_client.py --orbit BUILD/orbit --stubs DIR_WITH_orbit/v1/*_pb2.py [--data DIR]
"""
import argparse
import os
import re
import signal
import subprocess
import sys
import tempfile
import time

ENROLLED_AZIMUTHS = range(0, 360, 10)
QUERY_AZIMUTHS = [15, 25, 35, 45, 55, 65]  # between the enrolled views
COMPASS_OFFSET = 140.0                     # the device's compass disagrees with the model's


def parse_args():
    here = os.path.dirname(os.path.abspath(__file__))
    default_data = os.environ.get(
        "ORBIT_DATA", os.path.join(here, "..", "..", "..", "shared", "data"))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--orbit", required=True, help="the orbit binary")
    parser.add_argument("--stubs", required=True, help="folder holding orbit/v1/*_pb2*.py")
    parser.add_argument("--data", default=default_data, help="folder holding coil-100/")
    return parser.parse_args()


def coil(data, obj, azimuth):
    return os.path.join(data, "coil-100", "obj%d__%d.png" % (obj, azimuth))


class Server:
    """`orbit serve` on 127.0.0.1, port chosen by the server, stopped with SIGTERM."""

    def __init__(self, orbit, folder):
        self.log_path = os.path.join(folder, "serve.log")
        self.log = open(self.log_path, "w")
        self.process = subprocess.Popen(
            [orbit, "serve", "--db", os.path.join(folder, "models.db"),
             "--listen", "127.0.0.1:0"],
            stdout=self.log, stderr=subprocess.STDOUT)
        self.address = None
        deadline = time.time() + 60
        while time.time() < deadline and self.process.poll() is None:
            with open(self.log_path) as log:
                found = re.search(r"listening on (\S+)", log.read())
            if found:
                self.address = found.group(1)
                return
            time.sleep(0.05)
        raise RuntimeError("orbit serve did not start:\n" + open(self.log_path).read())

    def stop(self):
        self.process.send_signal(signal.SIGTERM)
        code = self.process.wait(timeout=30)
        self.log.close()
        return code


def main():
    args = parse_args()
    sys.path.insert(0, args.stubs)
    import grpc
    from orbit.v1 import models_pb2, models_pb2_grpc, recognition_pb2, recognition_pb2_grpc, types_pb2

    failures = []

    def check(condition, message):
        if not condition:
            failures.append(message)
            print("FAILED: " + message, file=sys.stderr)

    with tempfile.TemporaryDirectory(prefix="orbit_python_") as folder:
        server = Server(args.orbit, folder)
        try:
            for obj in (1, 2):
                command = [args.orbit, "enroll", "--server", server.address, "--name", "obj%d" % obj]
                for azimuth in ENROLLED_AZIMUTHS:
                    command += ["--image", coil(args.data, obj, azimuth), "--azimuth", str(azimuth)]
                subprocess.run(command, check=True, stdout=subprocess.DEVNULL)

            channel = grpc.insecure_channel(server.address)
            models = models_pb2_grpc.ModelsStub(channel)
            info = models.ServerInfo(models_pb2.ServerInfoRequest(), timeout=10)
            check(info.object_count == 2, "ServerInfo.object_count %d != 2" % info.object_count)
            listed = models.ListObjects(models_pb2.ListObjectsRequest(page_size=10), timeout=10)
            names = [o.name for o in listed.objects]
            check(names == ["obj1", "obj2"], "ListObjects names %r" % names)

            # Frames: even ones as descriptors computed by `orbit descriptor`, odd ones as PNGs.
            files = [coil(args.data, 2, a) for a in QUERY_AZIMUTHS]
            # In the server's variant (CEDD_SOFT_HSV_HOG -> cedd-soft-hsv-hog): its first 144
            # values are the frame's cedd field, any others its appearance field.
            variant = types_pb2.DescriptorVariant.Name(info.variant).lower().replace("_", "-")
            described = subprocess.run([args.orbit, "descriptor", "--variant", variant] + files,
                                       check=True, capture_output=True, text=True).stdout
            values = [bytes(int(v) for v in line.split()[1:]) for line in described.splitlines()]
            requests = [recognition_pb2.SessionRequest(
                open=recognition_pb2.SessionOptions(engine=recognition_pb2.ENGINE_VCI, top_k=2))]
            for k, azimuth in enumerate(QUERY_AZIMUTHS):
                frame = recognition_pb2.Frame(azimuth_deg=azimuth + COMPASS_OFFSET, timestamp_us=k)
                if k % 2 == 0:
                    frame.cedd = values[k][:144]
                    frame.appearance = values[k][144:]
                else:
                    with open(files[k], "rb") as png:
                        frame.image = png.read()
                requests.append(recognition_pb2.SessionRequest(frame=frame))

            recognition = recognition_pb2_grpc.RecognitionStub(channel)
            updates = list(recognition.Session(iter(requests), timeout=60))
            check(len(updates) == len(QUERY_AZIMUTHS),
                  "%d updates for %d frames" % (len(updates), len(QUERY_AZIMUTHS)))
            for k, update in enumerate(updates):
                check(update.frame_index == k, "update %d has frame_index %d" % (k, update.frame_index))
                check(update.timestamp_us == k, "update %d echoes timestamp %d" % (k, update.timestamp_us))
                check(1 <= len(update.candidates) <= 2,
                      "update %d has %d candidates" % (k, len(update.candidates)))
                check(0 <= update.confidence <= 1,
                      "update %d has confidence %f" % (k, update.confidence))
                check(update.HasField("pose") and 0 <= update.pose.azimuth_deg < 360,
                      "update %d has no pose in [0, 360)" % k)
                print("frame %d: %s confidence %.2f pose %.0f deg %s" % (
                    k, recognition_pb2.Decision.Name(update.decision), update.confidence,
                    update.pose.azimuth_deg,
                    ", ".join("%s %.3f" % (c.name, c.score) for c in update.candidates)))
            if updates and updates[-1].candidates:
                top = updates[-1].candidates[0].name
                check(top == "obj2", "top candidate after the last frame is %s, not obj2" % top)

            # A bad frame gets INVALID_ARGUMENT, as the proto says.
            bad = [requests[0], recognition_pb2.SessionRequest(
                frame=recognition_pb2.Frame(cedd=b"\x09" * 144, azimuth_deg=0))]
            try:
                list(recognition.Session(iter(bad), timeout=30))
                check(False, "a descriptor value of 9 was accepted")
            except grpc.RpcError as error:
                check(error.code() == grpc.StatusCode.INVALID_ARGUMENT,
                      "bad descriptor: %s, not INVALID_ARGUMENT" % error.code())
            channel.close()
        finally:
            code = server.stop()
        check(code == 0, "orbit serve exited %d after SIGTERM" % code)

    if failures:
        print("%d check(s) failed" % len(failures), file=sys.stderr)
        return 1
    print("python client: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
