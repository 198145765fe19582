#!/usr/bin/python3
"""Reads CAN frames from an slcan (Lawicel ASCII) device with python-can and logs them in
candump -L format (python-can's CanutilsLogWriter), as a robot computer's driver would.

Usage: slcan_capture.py DEVICE LOGFILE SECONDS
Opens DEVICE with interface="slcan" (python-can sends C, S6, O), receives for SECONDS, closes
the channel (C) and prints the number of frames received. Run with /usr/bin/python3: it needs
Debian's python3-can.
"""
import sys
import time

import can


def main() -> int:
    device, log_path, seconds = sys.argv[1], sys.argv[2], float(sys.argv[3])
    bus = can.Bus(interface="slcan", channel=device, bitrate=500000, sleep_after_open=0)
    writer = can.Logger(log_path)
    count = 0
    end = time.monotonic() + seconds
    try:
        while time.monotonic() < end:
            msg = bus.recv(timeout=0.1)
            if msg is not None:
                writer.on_message_received(msg)
                count += 1
    finally:
        writer.stop()
        bus.shutdown()
    print(count)
    return 0


if __name__ == "__main__":
    sys.exit(main())
