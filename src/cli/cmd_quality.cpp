// coxmesh quality: quality measures, Delaunay property and protection of the Coxeter triangulations of
// every affine type (thesis Ch. 2), as a table, JSON, CSV, Markdown or an SVG plot against d.

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "commands.h"
#include "common.h"
#include "coxmesh/io/atomic_file.h"
#include "coxmesh/quality/table_row.h"
#include "coxmesh/util/parse_number.h"

namespace coxmesh::cli {

namespace {

using quality::CoxeterQuality;
using quality::Family;

struct QualityOptions {
  std::vector<std::string> types;
  std::string dim;
  bool all = false;
  int max_dim = 8;
  bool json = false, csv = false, markdown = false, relative = false;
  std::string plot, measure = "thickness", y_scale = "auto";
};

using Row = quality::QualityRow;
using quality::numeric_keys;
Row make_row(const CoxeterQuality& q) { return quality::table_row(q); }

std::optional<double> value(const Row& r, const std::string& key) {
  for (const auto& [k, v] : r.numbers)
    if (k == key) return v;
  throw std::logic_error("quality: no column " + key);
}

int parse_int(const std::string& text, const std::string& what) {
  const std::optional<std::uint64_t> v = parse_unsigned(text);
  if (!v || *v > 1000) throw InputError(what + ": '" + printable(text) + "' is not an integer from 0 to 1000");
  return static_cast<int>(*v);
}

// "D" or "D..D2".
std::pair<int, int> parse_dim_range(const std::string& text) {
  const auto dots = text.find("..");
  const int lo = parse_int(text.substr(0, dots), "--dim");
  const int hi = dots == std::string::npos ? lo : parse_int(text.substr(dots + 2), "--dim");
  if (lo < 1 || hi < lo || hi > quality::kMaxRank)
    throw InputError("--dim must be D or D..D2 with 1 <= D <= D2 <= " + std::to_string(quality::kMaxRank) + ", got '" +
                     text + "'");
  return {lo, hi};
}

// The (family, d) pairs asked for, in family then dimension order.
std::vector<std::pair<Family, int>> requested_pairs(const QualityOptions& o) {
  if (o.max_dim < 1 || o.max_dim > quality::kMaxRank)
    throw InputError("--max-dim must be in 1.." + std::to_string(quality::kMaxRank));
  std::vector<Family> families;
  for (const std::string& t : o.types) families.push_back(quality::parse_family(t));
  const bool every_family = o.all || (families.empty() && !o.plot.empty());
  if (every_family && !families.empty()) throw InputError("--all cannot be combined with --type");
  if (every_family) families.assign(std::begin(quality::kAllFamilies), std::end(quality::kAllFamilies));
  if (families.empty()) throw InputError("give --type (one or more of A..G) or --all");

  std::vector<std::pair<Family, int>> pairs;
  for (Family f : families) {
    if (o.dim.empty()) {
      for (int d : quality::supported_affine_ranks(f, o.max_dim)) pairs.emplace_back(f, d);
      continue;
    }
    const auto [lo, hi] = parse_dim_range(o.dim);
    for (int d = lo; d <= hi; ++d) {
      if (every_family) {  // --all with --dim: the supported pairs in the range
        const auto ranks = quality::supported_affine_ranks(f, hi);
        if (std::find(ranks.begin(), ranks.end(), d) == ranks.end()) continue;
      } else {
        quality::check_affine_type(f, d);  // an explicit pair must exist
      }
      pairs.emplace_back(f, d);
    }
  }
  if (pairs.empty()) throw InputError("no supported (type, dimension) pair in the request");
  return pairs;
}

std::string fixed6(std::optional<double> v) {
  if (!v) return "-";
  std::ostringstream os;
  os << std::setprecision(6) << *v;
  return os.str();
}

// Columns of the human-readable and Markdown tables.
struct Column {
  std::string title, key;
};
std::vector<Column> table_columns(bool relative) {
  if (relative)
    return {{"h/L rel", "thickness_relative"},
            {"d·r/R", "radius_ratio_relative"},
            {"fatness rel", "fatness_relative"},
            {"h/R rel", "aspect_ratio_relative"}};
  return {{"L", "longest_edge"},
          {"l", "shortest_edge"},
          {"L/l", "edge_ratio"},
          {"h/L", "thickness"},
          {"h/(dL)", "thickness_normalized"},
          {"r/R", "radius_ratio"},
          {"vol/L^d", "fatness"},
          {"h/R", "aspect_ratio"}};
}

std::vector<std::vector<std::string>> table_cells(const std::vector<Row>& rows, bool relative,
                                                  std::vector<std::string>& header) {
  const auto cols = table_columns(relative);
  header = {"type", "d"};
  for (const auto& c : cols) header.push_back(c.title);
  if (!relative) header.insert(header.end(), {"Delaunay", "direct", "δ/L"});
  std::vector<std::vector<std::string>> cells;
  for (const Row& r : rows) {
    std::vector<std::string> line{quality::family_name(r.family), std::to_string(r.dimension)};
    for (const auto& c : cols) line.push_back(fixed6(value(r, c.key)));
    if (!relative) line.insert(line.end(), {r.delaunay, r.delaunay_direct, fixed6(value(r, "protection"))});
    cells.push_back(std::move(line));
  }
  return cells;
}

std::size_t display_width(const std::string& s) {  // UTF-8 code points
  return static_cast<std::size_t>(std::count_if(s.begin(), s.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

void print_table(const std::vector<Row>& rows, bool relative) {
  std::vector<std::string> header;
  const auto cells = table_cells(rows, relative, header);
  std::vector<std::size_t> width(header.size());
  for (std::size_t k = 0; k < header.size(); ++k) width[k] = display_width(header[k]);
  for (const auto& line : cells)
    for (std::size_t k = 0; k < line.size(); ++k) width[k] = std::max(width[k], display_width(line[k]));
  auto print = [&](const std::vector<std::string>& line) {
    for (std::size_t k = 0; k < line.size(); ++k)
      std::cout << (k ? "  " : "") << std::string(width[k] - display_width(line[k]), ' ') << line[k];
    std::cout << "\n";
  };
  print(header);
  for (const auto& line : cells) print(line);
}

void print_markdown(const std::vector<Row>& rows, bool relative) {
  std::vector<std::string> header;
  const auto cells = table_cells(rows, relative, header);
  auto print = [](const std::vector<std::string>& line) {
    std::cout << "|";
    for (const auto& c : line) std::cout << " " << c << " |";
    std::cout << "\n";
  };
  print(header);
  std::cout << "|";
  for (std::size_t k = 0; k < header.size(); ++k) std::cout << (k < 2 ? ":--|" : "--:|");
  std::cout << "\n";
  for (const auto& line : cells) print(line);
}

void print_csv(const std::vector<Row>& rows) {
  std::cout << "type,dimension";
  for (const auto& k : numeric_keys()) std::cout << "," << k;
  std::cout << ",delaunay,delaunay_direct\n";
  std::cout << std::setprecision(17);
  for (const Row& r : rows) {
    std::cout << quality::family_name(r.family) << "," << r.dimension;
    for (const auto& [k, v] : r.numbers) {
      std::cout << ",";
      if (v) std::cout << *v;
    }
    std::cout << "," << r.delaunay << "," << r.delaunay_direct << "\n";
  }
}

void print_json(const std::vector<Row>& rows) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const Row& r : rows) {
    nlohmann::ordered_json j;
    j["type"] = quality::family_name(r.family);
    j["dimension"] = r.dimension;
    for (const auto& [k, v] : r.numbers) j[k] = v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr);
    j["delaunay"] = r.delaunay;
    j["delaunay_direct"] = r.delaunay_direct;
    out.push_back(std::move(j));
  }
  std::cout << out.dump(1, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
}

// ---- SVG plot --------------------------------------------------------------------------------------

std::string number_text(double v) {
  std::ostringstream os;
  os << std::setprecision(3) << v;
  return os.str();
}

double nice_step(double range) {
  const double raw = range / 5, p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * p >= raw) return m * p;
  return 10 * p;
}

std::string svg_plot(const std::vector<Row>& rows, const std::string& measure, bool log_scale) {
  constexpr double W = 760, H = 480, left = 80, right = 150, top = 40, bottom = 60;
  const double pw = W - left - right, ph = H - top - bottom;
  double xmin = 1e9, xmax = -1e9, ymin = 1e300, ymax = -1e300;
  for (const Row& r : rows) {
    const auto v = value(r, measure);
    if (!v || (log_scale && *v <= 0)) continue;
    xmin = std::min<double>(xmin, r.dimension), xmax = std::max<double>(xmax, r.dimension);
    ymin = std::min(ymin, *v), ymax = std::max(ymax, *v);
  }
  if (xmin > xmax) throw InputError("--measure " + measure + " has no value to plot for the chosen rows");
  if (xmin == xmax) xmin -= 1, xmax += 1;
  double ylo, yhi, step;
  if (log_scale) {
    ylo = std::floor(std::log10(ymin)), yhi = std::ceil(std::log10(ymax));
    if (ylo == yhi) yhi += 1;
    step = std::max(1.0, std::ceil((yhi - ylo) / 10));
  } else {
    ylo = std::min(0.0, ymin), yhi = ymax > ylo ? ymax : ylo + 1;
    step = nice_step(yhi - ylo);
    yhi = std::ceil(yhi * (1 + 1e-9) / step) * step;
  }
  auto X = [&](double x) { return left + (x - xmin) / (xmax - xmin) * pw; };
  auto Y = [&](double y) { return top + ph - ((log_scale ? std::log10(y) : y) - ylo) / (yhi - ylo) * ph; };

  std::ostringstream s;
  s << std::setprecision(6);
  s << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H << "\" viewBox=\"0 0 " << W
    << " " << H << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
    << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << "<text x=\"" << left + pw / 2 << "\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">" << measure
    << " of the Coxeter triangulations against the dimension d</text>\n";
  // Grid, ticks and labels.
  for (double t = ylo; t <= yhi + 1e-9 * std::abs(yhi); t += step) {
    const double y = log_scale ? top + ph - (t - ylo) / (yhi - ylo) * ph : Y(t);
    s << "<line x1=\"" << left << "\" y1=\"" << y << "\" x2=\"" << left + pw << "\" y2=\"" << y
      << "\" stroke=\"#ddd\"/>\n<text x=\"" << left - 6 << "\" y=\"" << y + 4 << "\" text-anchor=\"end\">"
      << (log_scale ? "1e" + number_text(t) : number_text(t)) << "</text>\n";
  }
  const double xstep = std::max(1.0, std::ceil((xmax - xmin) / 12));
  for (double x = std::ceil(xmin); x <= xmax; x += xstep)
    s << "<line x1=\"" << X(x) << "\" y1=\"" << top + ph << "\" x2=\"" << X(x) << "\" y2=\"" << top + ph + 5
      << "\" stroke=\"black\"/>\n<text x=\"" << X(x) << "\" y=\"" << top + ph + 20 << "\" text-anchor=\"middle\">" << x
      << "</text>\n";
  s << "<line x1=\"" << left << "\" y1=\"" << top + ph << "\" x2=\"" << left + pw << "\" y2=\"" << top + ph
    << "\" stroke=\"black\"/>\n<line x1=\"" << left << "\" y1=\"" << top << "\" x2=\"" << left << "\" y2=\"" << top + ph
    << "\" stroke=\"black\"/>\n<text x=\"" << left + pw / 2 << "\" y=\"" << H - 15
    << "\" text-anchor=\"middle\">dimension d</text>\n<text transform=\"translate(20," << top + ph / 2
    << ") rotate(-90)\" text-anchor=\"middle\">" << measure << (log_scale ? " (log scale)" : "") << "</text>\n";
  // One polyline per family, with markers, and the legend.
  static const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2"};
  int legend = 0;
  for (Family f : quality::kAllFamilies) {
    std::ostringstream pts, marks;
    pts << std::setprecision(6);
    marks << std::setprecision(6);
    int count = 0;
    for (const Row& r : rows) {
      const auto v = value(r, measure);
      if (r.family != f || !v || (log_scale && *v <= 0)) continue;
      pts << (count++ ? " " : "") << X(r.dimension) << "," << Y(*v);
      marks << "<circle cx=\"" << X(r.dimension) << "\" cy=\"" << Y(*v) << "\" r=\"3\" fill=\""
            << colours[static_cast<int>(f)] << "\"/>\n";
    }
    if (count == 0) continue;
    s << "<polyline fill=\"none\" stroke=\"" << colours[static_cast<int>(f)] << "\" stroke-width=\"2\" points=\""
      << pts.str() << "\"/>\n"
      << marks.str();
    const double ly = top + 10 + 20 * legend++;
    s << "<line x1=\"" << left + pw + 20 << "\" y1=\"" << ly << "\" x2=\"" << left + pw + 45 << "\" y2=\"" << ly
      << "\" stroke=\"" << colours[static_cast<int>(f)] << "\" stroke-width=\"2\"/>\n<text x=\"" << left + pw + 52
      << "\" y=\"" << ly + 4 << "\">" << quality::family_name(f)
      << "\u0303<tspan dy=\"4\" font-size=\"10\">d</tspan></text>\n";
  }
  s << "</svg>\n";
  return s.str();
}

bool ends_with_svg(std::string name) {
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
  return name.size() > 4 && name.ends_with(".svg");
}

void run(const QualityOptions& o) {
  if (o.json + o.csv + o.markdown > 1) throw InputError("give at most one of --json, --csv and --markdown");
  const auto& keys = numeric_keys();
  if (std::find(keys.begin(), keys.end(), o.measure) == keys.end()) {
    std::string list;
    for (const auto& k : keys) list += (list.empty() ? "" : ", ") + k;
    throw InputError("unknown --measure '" + o.measure + "' (one of " + list + ")");
  }
  if (!o.plot.empty() && !ends_with_svg(o.plot))
    throw InputError("--plot writes SVG only: the file name must end in .svg, got '" + o.plot + "'");
  const auto pairs = requested_pairs(o);
  std::vector<Row> rows;
  for (const auto& [f, d] : pairs) rows.push_back(make_row(quality::coxeter_quality(f, d, 2)));

  if (!o.plot.empty()) {
    bool log_scale = o.y_scale == "log";
    if (o.y_scale == "auto") {
      double lo = 1e300, hi = 0;
      for (const Row& r : rows)
        if (auto v = value(r, o.measure); v && *v > 0) lo = std::min(lo, *v), hi = std::max(hi, *v);
      log_scale = hi > 0 && hi / lo > 50;
    }
    const std::string svg = svg_plot(rows, o.measure, log_scale);
    write_file_atomically(o.plot, [&svg](std::ostream& out) { out << svg; });
    if (!o.json && !o.csv && !o.markdown) return;
  }
  if (o.json)
    print_json(rows);
  else if (o.csv)
    print_csv(rows);
  else if (o.markdown)
    print_markdown(rows, o.relative);
  else
    print_table(rows, o.relative);
}

}  // namespace

void register_quality(CLI::App& app, int& status) {
  auto o = std::make_shared<QualityOptions>();
  CLI::App* cmd = app.add_subcommand(
      "quality", "quality, Delaunay property and protection of the Coxeter triangulations (thesis Ch. 2)");
  cmd->add_option("--type", o->types, "family A, B, C, D, E, F or G (repeat or separate with commas)")->delimiter(',');
  cmd->add_option("--dim", o->dim, "dimension D or range D..D2 (default: every supported d up to --max-dim)");
  cmd->add_flag("--all", o->all, "every family, every supported dimension up to --max-dim");
  cmd->add_option("--max-dim", o->max_dim, "largest dimension for --all or without --dim")->capture_default_str();
  cmd->add_flag("--json", o->json, "print a JSON array of rows");
  cmd->add_flag("--csv", o->csv, "print CSV with every column");
  cmd->add_flag("--markdown", o->markdown, "print a Markdown table");
  cmd->add_flag("--relative", o->relative, "table/Markdown: the measures relative to the regular simplex");
  cmd->add_option("--plot", o->plot, "write an SVG chart of --measure against d, one line per family");
  cmd->add_option("--measure", o->measure, "the measure plotted (any numeric JSON key)")->capture_default_str();
  cmd->add_option("--y-scale", o->y_scale, "plot scale: linear, log, or auto (log when values span > 50x)")
      ->check(CLI::IsMember({"auto", "linear", "log"}))
      ->capture_default_str();
  cmd->callback([o, &status] { status = run_guarded([&] { run(*o); }); });
}

}  // namespace coxmesh::cli
