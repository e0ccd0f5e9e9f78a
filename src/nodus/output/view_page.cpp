#include "nodus/output/view_page.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <queue>
#include <set>
#include <stdexcept>
#include <string_view>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "nodus/output/atomic_file.hpp"
#include "nodus/output/viewer_bundle.hpp"
#include "nodus/version.hpp"

namespace nodus::output {

namespace {

/// The fields of a contact element's record in the page (Float32 each; web/src/data.js reads them):
/// x_i (3), x_j (3), normal (3), gap, R_N, |T|, state (0 open, 1 stick, 2 slip, -1 no forces), beam_i,
/// beam_j, zone.
constexpr std::size_t kContactRecord = 16;
/// Channels of a node record before the measures: centre, g1, g2 (3 each).
constexpr std::size_t kGeometryChannels = 9;
constexpr double kLevels = 65535.0;  // 16-bit quantisation

/// A per-node measure drawn on the fibres: its page name, label and unit, and how it is made from a state's
/// node fields (its inputs must all be there) for a node of a beam of Young's modulus E [MPa].
struct Measure {
  std::string name, label, unit;
  std::vector<std::string> inputs;
  std::function<double(const std::vector<const std::vector<double>*>&, std::size_t node, double E)> value;
};

/// The unit of VTK node measure `name` (docs/output.md): e.. [-], q.., k. [1/mm], m.. [1/mm^2].
std::string raw_unit(const std::string& name) {
  if (name.empty() || name[0] == 'e') return "-";
  if (name[0] == 'm') return "1/mm^2";
  return "1/mm";
}

/// The measures the page offers: the derived ones, then the raw fields asked for.
std::vector<Measure> measures(const ViewOptions& options) {
  std::vector<Measure> list = {
      {"e33",
       "axial strain e33",
       "-",
       {"e33"},
       [](const auto& in, std::size_t n, double) { return (*in[0])[n]; }},
      {"axial_stress",
       "axial stress E e33",
       "MPa",
       {"e33"},
       [](const auto& in, std::size_t n, double E) { return E * (*in[0])[n]; }},
      {"curvature",
       "curvature sqrt(k1^2 + k2^2)",
       "1/mm",
       {"k1", "k2"},
       [](const auto& in, std::size_t n, double) { return std::hypot((*in[0])[n], (*in[1])[n]); }},
  };
  for (const std::string& f : options.raw_fields)
    list.push_back(
        {f, f, raw_unit(f), {f}, [](const auto& in, std::size_t n, double) { return (*in[0])[n]; }});
  return list;
}

std::string base64(const std::uint8_t* data, std::size_t size) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < size; i += 3) {
    const std::uint32_t v = (data[i] << 16) | (data[i + 1] << 8) | data[i + 2];
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  if (i < size) {
    const std::uint32_t v = (data[i] << 16) | (i + 1 < size ? data[i + 1] << 8 : 0);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < size ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::size_t base64_size(std::size_t bytes) {
  return (bytes + 2) / 3 * 4;
}

int total_nodes(const ResultRun& run) {
  int n = 0;
  for (const ResultBeam& b : run.beams) n = std::max(n, b.first_node + b.node_count);
  return n;
}

/// Always-on checks of the run's arrays (an API precondition: a reader or a test built them).
void check_run(const ResultRun& run) {
  const std::size_t n = static_cast<std::size_t>(total_nodes(run));
  if (run.states.empty()) throw std::invalid_argument(fmt::format("run '{}': no states to show", run.name));
  for (const ResultState& s : run.states) {
    if (s.centre.size() != n || s.g1.size() != n || s.g2.size() != n)
      throw std::invalid_argument(fmt::format("run '{}', step {}: {} centres, {} g1, {} g2 for {} nodes",
                                              run.name, s.step, s.centre.size(), s.g1.size(), s.g2.size(),
                                              n));
    for (const auto& [name, values] : s.node_fields)
      if (values.size() != n)
        throw std::invalid_argument(fmt::format("run '{}', step {}: node field {} has {} values for {} nodes",
                                                run.name, s.step, name, values.size(), n));
    const ResultContacts& c = s.contacts;
    const std::size_t m = c.size();
    const bool forces = !c.normal_force.empty();
    if (c.x_j.size() != m || (!c.normal.empty() && c.normal.size() != m) || c.beam_i.size() != m ||
        c.beam_j.size() != m || c.gap.size() != m || (!c.zone.empty() && c.zone.size() != m) ||
        (forces && (c.normal_force.size() != m || c.tangential_force.size() != m || c.state.size() != m)))
      throw std::invalid_argument(
          fmt::format("run '{}', step {}: the contact elements' columns differ in length", run.name, s.step));
    for (std::size_t e = 0; e < m; ++e)
      if (c.beam_i[e] < 0 || c.beam_j[e] < 0 || c.beam_i[e] >= static_cast<int>(run.beams.size()) ||
          c.beam_j[e] >= static_cast<int>(run.beams.size()))
        throw std::invalid_argument(fmt::format(
            "run '{}', step {}: contact element {} names a beam that is not there", run.name, s.step, e));
  }
}

/// The bytes a state takes in the page (base64 of its node and contact records, and its JSON row).
std::size_t state_bytes(const ResultState& s, std::size_t nodes, std::size_t channels) {
  return base64_size(nodes * channels * 2) + base64_size(s.contacts.size() * kContactRecord * 4) + 100;
}

/// The run and its branches, depth first, with their page names ("main", "a", "a/b" for a branch b of a).
void flatten(const ResultRun& run, const std::string& name, bool main,
             std::vector<std::pair<std::string, const ResultRun*>>& out) {
  out.emplace_back(name, &run);
  for (const ResultRun& b : run.branches) flatten(b, main ? b.name : name + "/" + b.name, false, out);
}

double finite_or(double v, double fallback) {
  return std::isfinite(v) ? v : fallback;
}

/// One run's part of the page: its beams, stages, kept states and their records.
nlohmann::ordered_json run_json(const std::string& name, const ResultRun& run,
                                const std::vector<Measure>& all, double keep_fraction) {
  const std::size_t n = static_cast<std::size_t>(total_nodes(run));
  // The measures whose inputs every state has.
  std::vector<const Measure*> used;
  for (const Measure& m : all) {
    bool present = true;
    for (const ResultState& s : run.states)
      for (const std::string& in : m.inputs) present = present && s.node_fields.count(in) > 0;
    if (present) used.push_back(&m);
  }
  const std::size_t channels = kGeometryChannels + used.size();

  std::vector<std::size_t> stage_ends;
  for (std::size_t i = 0; i < run.states.size(); ++i)
    if (i + 1 == run.states.size() || run.states[i + 1].stage != run.states[i].stage) stage_ends.push_back(i);
  const std::size_t keep =
      keep_fraction >= 1.0
          ? run.states.size()
          : std::max<std::size_t>(2, static_cast<std::size_t>(run.states.size() * keep_fraction));
  const std::vector<std::size_t> kept = kept_states(run.states.size(), keep, stage_ends);

  std::vector<double> young(n, 0.0);
  for (const ResultBeam& b : run.beams)
    for (int k = 0; k < b.node_count; ++k)
      young[static_cast<std::size_t>(b.first_node + k)] = b.young_modulus;

  // Every channel's values of state s, node by node (channel-major), in double.
  const auto channel_values = [&](const ResultState& s, std::vector<double>& out) {
    out.assign(channels * n, 0.0);
    for (std::size_t i = 0; i < n; ++i)
      for (int d = 0; d < 3; ++d) {
        out[(0 + d) * n + i] = s.centre[i][d];
        out[(3 + d) * n + i] = s.g1[i][d];
        out[(6 + d) * n + i] = s.g2[i][d];
      }
    for (std::size_t k = 0; k < used.size(); ++k) {
      std::vector<const std::vector<double>*> in;
      for (const std::string& f : used[k]->inputs) in.push_back(&s.node_fields.at(f));
      for (std::size_t i = 0; i < n; ++i)
        out[(kGeometryChannels + k) * n + i] = used[k]->value(in, i, young[i]);
    }
  };

  // Ranges over the kept states, then the quantisation of each channel.
  std::vector<double> lo(channels, std::numeric_limits<double>::infinity());
  std::vector<double> hi(channels, -std::numeric_limits<double>::infinity());
  std::vector<double> values;
  for (std::size_t k : kept) {
    channel_values(run.states[k], values);
    for (std::size_t c = 0; c < channels; ++c)
      for (std::size_t i = 0; i < n; ++i) {
        const double v = values[c * n + i];
        if (!std::isfinite(v)) continue;
        lo[c] = std::min(lo[c], v);
        hi[c] = std::max(hi[c], v);
      }
  }
  std::vector<Quantisation> quant(channels);
  for (std::size_t c = 0; c < channels; ++c) {
    if (!(lo[c] <= hi[c])) lo[c] = hi[c] = 0.0;  // no finite value at all
    quant[c] = {lo[c], (hi[c] - lo[c]) / kLevels};
  }

  nlohmann::ordered_json j;
  j["name"] = name;
  j["node_count"] = n;
  nlohmann::ordered_json beams = nlohmann::ordered_json::array();
  for (const ResultBeam& b : run.beams)
    beams.push_back({{"name", b.name},
                     {"radius", b.radius},
                     {"E", b.young_modulus},
                     {"first", b.first_node},
                     {"count", b.node_count},
                     {"tool", b.tool}});
  j["beams"] = beams;
  nlohmann::ordered_json stages = nlohmann::ordered_json::array();
  for (const ResultStage& s : run.stages)
    stages.push_back({{"name", s.name}, {"start", s.start_time}, {"end", s.end_time}});
  j["stages"] = stages;
  j["state_count"] = run.states.size();  // before decimation
  nlohmann::ordered_json q = nlohmann::ordered_json::array();
  for (const Quantisation& x : quant) q.push_back({x.lo, x.step});
  j["quant"] = q;
  nlohmann::ordered_json ms = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < used.size(); ++k)
    ms.push_back({{"name", used[k]->name},
                  {"label", used[k]->label},
                  {"unit", used[k]->unit},
                  {"channel", kGeometryChannels + k},
                  {"range", {lo[kGeometryChannels + k], hi[kGeometryChannels + k]}}});
  j["measures"] = ms;

  nlohmann::ordered_json states = nlohmann::ordered_json::array();
  nlohmann::ordered_json nodes = nlohmann::ordered_json::array();
  nlohmann::ordered_json contacts = nlohmann::ordered_json::array();
  std::array<double, 2> normal_range{0.0, 0.0}, tangential_range{0.0, 0.0};
  std::vector<std::uint8_t> bytes;
  for (std::size_t k : kept) {
    const ResultState& s = run.states[k];
    states.push_back({{"index", k},
                      {"step", s.step},
                      {"time", s.load_time},
                      {"stage", s.stage},
                      {"contacts", s.contacts.size()}});
    channel_values(s, values);
    bytes.assign(channels * n * 2, 0);
    for (std::size_t c = 0; c < channels; ++c)
      for (std::size_t i = 0; i < n; ++i) {
        const double v = values[c * n + i];
        const double t = quant[c].step > 0.0 && std::isfinite(v) ? (v - quant[c].lo) / quant[c].step : 0.0;
        const auto u = static_cast<std::uint16_t>(std::clamp(std::lround(t), 0L, 65535L));
        bytes[2 * (c * n + i)] = static_cast<std::uint8_t>(u & 0xff);  // little-endian, as JS reads it
        bytes[2 * (c * n + i) + 1] = static_cast<std::uint8_t>(u >> 8);
      }
    nodes.push_back(base64(bytes.data(), bytes.size()));

    const ResultContacts& ct = s.contacts;
    const bool forces = !ct.normal_force.empty();
    std::vector<float> record(ct.size() * kContactRecord);
    for (std::size_t e = 0; e < ct.size(); ++e) {
      float* r = &record[e * kContactRecord];
      for (int d = 0; d < 3; ++d) {
        r[d] = static_cast<float>(ct.x_i[e][d]);
        r[3 + d] = static_cast<float>(ct.x_j[e][d]);
        r[6 + d] = ct.normal.size() == ct.size() ? static_cast<float>(ct.normal[e][d]) : 0.0f;
      }
      r[9] = static_cast<float>(ct.gap[e]);
      const double nan = std::numeric_limits<double>::quiet_NaN();
      const double rn = forces ? ct.normal_force[e] : nan, t = forces ? ct.tangential_force[e] : nan;
      r[10] = static_cast<float>(rn);
      r[11] = static_cast<float>(t);
      const std::string st = forces ? ct.state[e] : std::string();
      r[12] = st == "open" ? 0.0f : st == "stick" ? 1.0f : st == "slip" ? 2.0f : -1.0f;
      r[13] = static_cast<float>(ct.beam_i[e]);
      r[14] = static_cast<float>(ct.beam_j[e]);
      r[15] = ct.zone.empty() ? -1.0f : static_cast<float>(ct.zone[e]);
      normal_range[1] = std::max(normal_range[1], finite_or(rn, 0.0));
      tangential_range[1] = std::max(tangential_range[1], finite_or(t, 0.0));
    }
    std::vector<std::uint8_t> raw(record.size() * 4);
    for (std::size_t i = 0; i < record.size(); ++i) {
      std::uint32_t u;
      std::memcpy(&u, &record[i], 4);
      for (int b = 0; b < 4; ++b) raw[4 * i + b] = static_cast<std::uint8_t>(u >> (8 * b));
    }
    contacts.push_back(base64(raw.data(), raw.size()));
  }
  j["states"] = states;
  j["contact_ranges"] = {{"normal_force", normal_range}, {"tangential_force", tangential_range}};
  j["nodes"] = nodes;
  j["contacts"] = contacts;
  return j;
}

std::string html_escape(std::string_view s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

/// JSON text safe inside a <script> element: every '<' (only in its strings) written as the escape \u003c.
std::string json_in_script(std::string_view json) {
  std::string out;
  out.reserve(json.size());
  for (char c : json) {
    if (c == '<')
      out += "\\u003c";
    else
      out += c;
  }
  return out;
}

/// A script safe inside a <script> element: "</script" (which can only be in a string, a regular expression
/// or a comment of it) written "<\/script", which reads the same there.
std::string script_in_script(std::string_view script) {
  std::string out;
  out.reserve(script.size());
  for (std::size_t i = 0; i < script.size(); ++i) {
    out += script[i];
    if (script[i] == '<' && i + 7 < script.size() && script[i + 1] == '/') {
      std::string next(script.substr(i + 2, 6));
      std::transform(next.begin(), next.end(), next.begin(), [](unsigned char c) { return std::tolower(c); });
      if (next == "script") out += '\\';
    }
  }
  return out;
}

}  // namespace

std::vector<std::size_t> kept_states(std::size_t count, std::size_t keep,
                                     const std::vector<std::size_t>& stage_ends) {
  std::set<std::size_t> kept;
  if (keep >= count) {
    for (std::size_t i = 0; i < count; ++i) kept.insert(i);
    return {kept.begin(), kept.end()};
  }
  if (count == 0) return {};
  kept.insert(0);
  kept.insert(count - 1);
  for (std::size_t e : stage_ends)
    if (kept.size() < keep && e < count) kept.insert(e);
  // Then the middle of the widest gap between kept states, again and again.
  std::priority_queue<std::pair<std::size_t, std::size_t>> gaps;  // (width, first state of the gap)
  for (auto it = kept.begin(); std::next(it) != kept.end(); ++it) gaps.emplace(*std::next(it) - *it, *it);
  while (kept.size() < keep && !gaps.empty() && gaps.top().first > 1) {
    const auto [width, first] = gaps.top();
    gaps.pop();
    const std::size_t middle = first + width / 2;
    kept.insert(middle);
    gaps.emplace(middle - first, first);
    gaps.emplace(first + width - middle, middle);
  }
  return {kept.begin(), kept.end()};
}

std::string view_page_json(const ResultRun& run, const ViewOptions& options) {
  std::vector<std::pair<std::string, const ResultRun*>> runs;
  flatten(run, run.name.empty() ? "main" : run.name, true, runs);
  const std::vector<Measure> all = measures(options);
  std::uintmax_t total = 0;
  for (const auto& [name, r] : runs) {
    check_run(*r);
    const std::size_t n = static_cast<std::size_t>(total_nodes(*r));
    for (const ResultState& s : r->states) total += state_bytes(s, n, kGeometryChannels + all.size());
  }
  const double fraction =
      total <= options.max_bytes ? 1.0 : static_cast<double>(options.max_bytes) / static_cast<double>(total);

  nlohmann::ordered_json page;
  page["format"] = "nodus-view 1";
  page["title"] = options.title.empty() ? (run.name.empty() ? std::string("main") : run.name) : options.title;
  page["generator"] = fmt::format("nodus {} (commit {})", nodus::version(), nodus::commit());
  page["decimated"] = fraction < 1.0;
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const auto& [name, r] : runs) list.push_back(run_json(name, *r, all, fraction));
  page["runs"] = list;
  return page.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

std::string view_page_html(const ResultRun& run, const ViewOptions& options) {
  const std::string_view bundle = viewer_bundle();
  if (bundle.empty())
    throw ViewerUnavailable(
        "this nodus was built without the viewer's page script: run scripts/setup.sh (it runs `npm ci` in "
        "web/), "
        "then build nodus again");
  const std::string json = view_page_json(run, options);
  const std::string title = options.title.empty() ? run.name : options.title;
  std::string html;
  html.reserve(json.size() + bundle.size() + 1024);
  html += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  html += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  html += fmt::format("<meta name=\"generator\" content=\"nodus {}\">\n", html_escape(nodus::version()));
  html += "<title>nodus view: " + html_escape(title) + "</title>\n</head>\n<body>\n";
  html += "<script id=\"nodus-data\" type=\"application/json\">";
  html += json_in_script(json);
  html += "</script>\n<script>";
  html += script_in_script(bundle);
  html += "</script>\n</body>\n</html>\n";
  return html;
}

void write_view_page(const ResultRun& run, const std::filesystem::path& html, ViewOptions options) {
  write_file_atomically(html, view_page_html(run, options));
}

}  // namespace nodus::output
