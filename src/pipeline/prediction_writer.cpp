#include "abbe/pipeline/prediction_writer.hpp"

#include <cmath>

#include "abbe/io/fixed6.hpp"
#include "abbe/io/row_text.hpp"
#include "abbe/io/units.hpp"

namespace abbe::pipeline {
namespace {

constexpr std::size_t kChunk = std::size_t{1} << 16;

double l1(const Eigen::Vector3d& v) { return std::abs(v.x()) + std::abs(v.y()) + std::abs(v.z()); }

// Three numbers, each after its separator.
template <class Out, std::size_t N0, std::size_t N1, std::size_t N2>
void num3(Out& out, const Eigen::Vector3d& v, const char (&s0)[N0], const char (&s1)[N1],
          const char (&s2)[N2]) {
  out.text(s0);
  out.num(v.x());
  out.text(s1);
  out.num(v.y());
  out.text(s2);
  out.num(v.z());
}

}  // namespace

PredictionWriter::PredictionWriter(PathFormat format, std::vector<model::ModelKind> kinds,
                                   ByteSink sink, bool aligned, bool uncertainty)
    : format_(format),
      kinds_(std::move(kinds)),
      sink_(std::move(sink)),
      aligned_(aligned),
      uncertain_(uncertainty) {
  for (auto k : kinds_) {
    const model::ModelDescriptor& d = model::descriptor(k);
    second_order_.push_back(d.second_order);
    json_keys_.push_back(fmt::format(", \"{}\": {{\"px\": ", d.name));
    row_max_ += 16 * (io::kFixed6MaxChars + 8) + json_keys_.back().size();
    if (aligned_) row_max_ += 4 * (io::kFixed6MaxChars + 10);
    if (uncertain_) row_max_ += 3 * (io::kFixed6MaxChars + 10);
    if (aligned_ && uncertain_) row_max_ += 3 * (io::kFixed6MaxChars + 12);
  }
  u_um_.assign(kinds_.size(), Eigen::Vector3d::Zero());
  u_aligned_um_.assign(kinds_.size(), Eigen::Vector3d::Zero());
  pred_.resize(kinds_.size());
  aligned_um_.assign(kinds_.size(), Eigen::Vector3d::Zero());
  buf_.reserve(kChunk + row_max_);
  const bool all = kinds_.size() > 1;
  if (format_ == PathFormat::csv) {
    std::string header = all ? "x,y,z,line" : "x,y,z,px,py,pz,dx,dy,dz,d";
    for (std::size_t i = 0; i < kinds_.size(); ++i) {
      const std::string s =
          all ? "_" + std::string(model::descriptor(kinds_[i]).column_suffix) : "";
      if (all) header += fmt::format(",px{0},py{0},pz{0},dx{0},dy{0},dz{0},d{0}", s);
      if (second_order_[i]) header += fmt::format(",dx2{0},dy2{0},dz2{0}", s);
      if (aligned_) header += fmt::format(",adx{0},ady{0},adz{0},ad{0}", s);
      if (uncertain_) header += fmt::format(",u_dx{0},u_dy{0},u_dz{0}", s);
      if (aligned_ && uncertain_) header += fmt::format(",u_adx{0},u_ady{0},u_adz{0}", s);
    }
    if (!all) header += ",line";
    put(header + "\n");
  } else {
    put("{\"points\": [\n");
  }
}

void PredictionWriter::write(const model::EvalPoint& p, std::size_t line,
                             const std::vector<model::Deviation>& devs,
                             const std::vector<double>& norms,
                             const std::vector<Eigen::Vector3d>& aligned_um) {
  aligned_um_ = aligned_um;
  write_row(p, line, devs, norms);
}

void PredictionWriter::write_uncertain(const model::EvalPoint& p, std::size_t line,
                                       const std::vector<model::Deviation>& devs,
                                       const std::vector<double>& norms,
                                       const std::vector<Eigen::Vector3d>& u_um) {
  u_um_ = u_um;
  write_row(p, line, devs, norms);
}

void PredictionWriter::write_uncertain(const model::EvalPoint& p, std::size_t line,
                                       const std::vector<model::Deviation>& devs,
                                       const std::vector<double>& norms,
                                       const std::vector<Eigen::Vector3d>& aligned_um,
                                       const std::vector<Eigen::Vector3d>& u_um,
                                       const std::vector<Eigen::Vector3d>& u_aligned_um) {
  aligned_um_ = aligned_um;
  u_um_ = u_um;
  u_aligned_um_ = u_aligned_um;
  write_row(p, line, devs, norms);
}

void PredictionWriter::write_row(const model::EvalPoint& p, std::size_t line,
                                 const std::vector<model::Deviation>& devs,
                                 const std::vector<double>& norms) {
  if (line != line_ || line_size_ == 0) {
    line_ = line;
    line_size_ = static_cast<std::size_t>(
        io::write_decimal(line_text_.data(), static_cast<unsigned long long>(line)) -
        line_text_.data());
  }
  // The in-place formatter takes the row when every number fits; the sum of
  // the magnitudes of the nominal point and the deviations bounds every
  // number of the row (|p + 1e-3·e| and |e| are at most that sum), so it is a
  // cheap sufficient test (NaN and infinity fail it, and a row that fails
  // takes the appending path, which writes the same text).
  double magnitude = l1(p.p);
  for (std::size_t i = 0; i < kinds_.size(); ++i) {
    const model::Deviation& d = devs[i];
    pred_[i] = p.p + units::kMmPerUm * d.e_um;
    magnitude += l1(d.e_um) + l1(d.second_order_um);
    if (aligned_) magnitude += 2.0 * l1(aligned_um_[i]);
    if (uncertain_) magnitude += l1(u_um_[i]) + l1(u_aligned_um_[i]);
  }
  if (io::fixed6_fits(magnitude)) {
    const std::size_t old_size = buf_.size();
    buf_.resize(old_size + row_max_);
    const io::InPlaceRow out = row(io::InPlaceRow{buf_.data() + old_size}, p, devs, norms);
    buf_.resize(static_cast<std::size_t>(out.p - buf_.data()));
  } else {
    row(io::AppendedRow{buf_}, p, devs, norms);
  }
  ++points_;
  if (buf_.size() >= kChunk) flush();
}

void PredictionWriter::finish(std::string_view summary_json) {
  if (format_ == PathFormat::json) {
    put("\n],\n\"summary\": ");
    put(summary_json);
    put("}\n");
  }
  flush();
}

template <class Out>
Out PredictionWriter::row(Out out, const model::EvalPoint& p,
                          const std::vector<model::Deviation>& devs,
                          const std::vector<double>& norms) const {
  const bool all = kinds_.size() > 1;
  if (format_ == PathFormat::csv) {
    num3(out, p.p, "", ",", ",");
    if (all) {
      out.ch(',');
      out.block(line_text_, line_size_);
    }
    for (std::size_t i = 0; i < kinds_.size(); ++i) {
      const model::Deviation& d = devs[i];
      num3(out, pred_[i], ",", ",", ",");
      num3(out, d.e_um, ",", ",", ",");
      out.ch(',');
      out.num(norms[i]);
      if (second_order_[i]) num3(out, d.second_order_um, ",", ",", ",");
      if (aligned_) {
        num3(out, aligned_um_[i], ",", ",", ",");
        out.ch(',');
        out.num(aligned_um_[i].norm());
      }
      if (uncertain_) num3(out, u_um_[i], ",", ",", ",");
      if (aligned_ && uncertain_) num3(out, u_aligned_um_[i], ",", ",", ",");
    }
    if (!all) {
      out.ch(',');
      out.block(line_text_, line_size_);
    }
    out.ch('\n');
  } else {
    out.text(points_ ? ",\n{\"x\": " : "{\"x\": ");
    num3(out, p.p, "", ", \"y\": ", ", \"z\": ");
    out.text(", \"line\": ");
    out.block(line_text_, line_size_);
    for (std::size_t i = 0; i < kinds_.size(); ++i) {
      const model::Deviation& d = devs[i];
      out.text(json_keys_[i]);
      num3(out, pred_[i], "", ", \"py\": ", ", \"pz\": ");
      num3(out, d.e_um, ", \"dx\": ", ", \"dy\": ", ", \"dz\": ");
      out.text(", \"d\": ");
      out.num(norms[i]);
      if (second_order_[i])
        num3(out, d.second_order_um, ", \"dx2\": ", ", \"dy2\": ", ", \"dz2\": ");
      if (aligned_) {
        num3(out, aligned_um_[i], ", \"adx\": ", ", \"ady\": ", ", \"adz\": ");
        out.text(", \"ad\": ");
        out.num(aligned_um_[i].norm());
      }
      if (uncertain_) num3(out, u_um_[i], ", \"u_dx\": ", ", \"u_dy\": ", ", \"u_dz\": ");
      if (aligned_ && uncertain_)
        num3(out, u_aligned_um_[i], ", \"u_adx\": ", ", \"u_ady\": ", ", \"u_adz\": ");
      out.ch('}');
    }
    out.ch('}');
  }
  return out;
}

void PredictionWriter::flush() {
  sink_(buf_.data(), buf_.size());
  buf_.clear();
}

}  // namespace abbe::pipeline
