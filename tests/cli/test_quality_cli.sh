#!/usr/bin/env bash
# End-to-end tests of `coxmesh quality` ($COXMESH): JSON keys and values, CSV, Markdown, errors and
# exit codes, and the SVG plot (thesis Ch. 2).
set -euo pipefail
source "$(dirname "$0")/lib.sh"

# JSON: one row per (type, d), every documented key, values of thesis §2.4.
json=$("$bin" quality --type A,C --dim 2..4 --json)
check "json rows" "6" "$(grep -c '"type":' <<<"$json")"
for key in type dimension longest_edge shortest_edge edge_ratio thickness thickness_normalized radius_ratio \
           fatness aspect_ratio delaunay protection; do
  check "json key $key" "6" "$(grep -c "\"$key\":" <<<"$json")"
done
check "A2 protection" '"protection": 0.5773502' "$(grep -o '"protection": 0.5773502' <<<"$json" | head -1)"
check "A delaunay yes" "3" "$(grep -c '"delaunay": "yes"' <<<"$json")"
check "C delaunay degenerate" "3" "$(grep -c '"delaunay": "degenerate"' <<<"$json")"
json=$("$bin" quality --type D --dim 4 --json)
check "D4 not Delaunay" '"delaunay": "no"' "$(grep -o '"delaunay": "no"' <<<"$json")"
check "D4 protection null" '"protection": null' "$(grep -o '"protection": null' <<<"$json")"
check "E8 volume" '"volume": 1.43527' "$("$bin" quality --type E --dim 8 --json | grep -o '"volume": 1.43527')"

# CSV: a header and one line per row, all with the same number of fields.
"$bin" quality --all --max-dim 3 --csv > "$tmp/q.csv"
check "csv header" "type,dimension,longest_edge" "$(head -1 "$tmp/q.csv" | cut -d, -f1-3)"
check "csv lines" "8" "$(wc -l < "$tmp/q.csv")"  # header + A1 A2 A3 B3 C2 C3 G2
check "csv field counts" "1" "$(awk -F, '{print NF}' "$tmp/q.csv" | sort -u | wc -l)"
check "csv A3 row" "A,3,1," "$(grep '^A,3,' "$tmp/q.csv" | cut -d, -f1-3),"

# Table and Markdown.
check "table rows" "6" "$("$bin" quality --type E,F,G | wc -l)"  # header + E6 E7 E8 F4 G2
check "markdown header" "| type | d |" "$("$bin" quality --type G --markdown | head -1 | cut -c1-12)"
check "markdown rows" "3" "$("$bin" quality --type G --markdown | wc -l)"
check "relative table" "d·r/R" "$("$bin" quality --type A --dim 3 --relative | head -1 | grep -o 'd·r/R')"

# Errors: one line, exit status 1.
fails_with "D3 unsupported" "no root system of type D and rank 3" "$bin" quality --type D --dim 3
fails_with "E5 unsupported" "type E supports d = 6, 7 or 8" "$bin" quality --type E --dim 5
fails_with "B2 not affine" "B~_d needs d >= 3" "$bin" quality --type B --dim 2
fails_with "unknown type" "unknown root system type 'H'" "$bin" quality --type H --dim 3
fails_with "bad range" "--dim must be" "$bin" quality --type A --dim 5..3
fails_with "dim not a number" "is not an integer" "$bin" quality --type A --dim x
fails_with "no type" "give --type" "$bin" quality --dim 3
fails_with "two formats" "at most one of" "$bin" quality --type A --dim 2 --json --csv
fails_with "bad measure" "unknown --measure" "$bin" quality --type A --dim 2 --plot "$tmp/x.svg" --measure bogus
fails_with "png refused" "SVG only" "$bin" quality --type A --plot "$tmp/x.png"
fails_with "bad directory" "cannot write" "$bin" quality --type A --plot "$tmp/none/x.svg"
status=0; "$bin" quality --type D --dim 3 2>/dev/null || status=$?
check "exit code" "1" "$status"

# Plot: a complete SVG with one polyline per family and a legend, written atomically (no leftovers).
"$bin" quality --plot "$tmp/plot.svg" --type A,B,C --max-dim 6
check "svg written" "yes" "$([[ -s "$tmp/plot.svg" ]] && echo yes || echo no)"
check "svg prolog" '<?xml version="1.0" encoding="UTF-8"?>' "$(head -1 "$tmp/plot.svg")"
check "svg closed" "</svg>" "$(tail -1 "$tmp/plot.svg")"
check "svg polylines" "3" "$(grep -c '<polyline' "$tmp/plot.svg")"
check "svg no temp files" "1" "$(find "$tmp" -name '*plot.svg*' | wc -l)"
"$bin" quality --plot "$tmp/fat.svg" --all --measure fatness --y-scale log
check "svg log scale" "1" "$(grep -c 'fatness (log scale)' "$tmp/fat.svg")"
if command -v python3 >/dev/null; then
  check "svg well-formed" "ok" "$(python3 -c 'import sys, xml.dom.minidom as m; [m.parse(f) for f in sys.argv[1:]]; print("ok")' "$tmp/plot.svg" "$tmp/fat.svg")"
fi

finish
