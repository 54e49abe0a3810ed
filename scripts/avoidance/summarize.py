#!/usr/bin/env python3
"""Summarise `stereo avoid --method both` JSON lines: decisions per method, agreement between the
methods, frame rate, and accuracy against the hand labels (docs/figures/avoidance/labels.csv).
Standard library only. Usage: summarize.py LABELS.csv CLIP=FILE.jsonl [CLIP=FILE.jsonl ...]"""
import collections
import csv
import json
import statistics
import sys


def main() -> None:
    labels = {}
    with open(sys.argv[1], newline="") as f:
        for row in csv.DictReader(f):
            labels[(row["clip"], row["frame"])] = row["expected"]
    print("| run | frames | threshold: F/L/R | fuzzy: F/L/R/B | agreement | mean ms | fps | labelled | threshold acc. | fuzzy acc. |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for arg in sys.argv[2:]:
        clip, path = arg.split("=", 1)
        frames = [json.loads(line) for line in open(path) if line.strip()]
        t = collections.Counter(fr["threshold"]["decision"] for fr in frames)
        z = collections.Counter(fr["fuzzy"]["decision"] for fr in frames)
        agree = sum(fr["threshold"]["decision"] == fr["fuzzy"]["decision"] for fr in frames)
        ms = statistics.mean(fr["ms"] for fr in frames)
        labelled = [(fr, labels[(clip, fr["frame"])]) for fr in frames if (clip, fr["frame"]) in labels]
        acc_t = sum(fr["threshold"]["decision"] == e for fr, e in labelled)
        acc_z = sum(fr["fuzzy"]["decision"] == e for fr, e in labelled)
        n = len(labelled)
        print(f"| {path.split('/')[-1]} | {len(frames)} | {t['forward']}/{t['left']}/{t['right']} | "
              f"{z['forward']}/{z['left']}/{z['right']}/{z['backwards']} | "
              f"{100 * agree / len(frames):.0f} % | {ms:.0f} | {1000 / ms:.2f} | {n} | "
              f"{acc_t}/{n} | {acc_z}/{n} |")


if __name__ == "__main__":
    main()
