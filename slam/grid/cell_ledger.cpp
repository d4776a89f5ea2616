#include "slam/grid/cell_ledger.hpp"

#include <algorithm>
#include <limits>

namespace lifelong::slam {

CellLedger::Entry& CellLedger::At(CellIndex c) {
  std::unique_ptr<Chunk>& chunk = chunks_[chunk::Key(chunk::Of(c.x), chunk::Of(c.y))];
  if (!chunk) chunk = std::make_unique<Chunk>();
  return (*chunk)[static_cast<std::size_t>(chunk::Offset(c))];
}

const CellLedger::Entry* CellLedger::Find(CellIndex c) const {
  const auto it = chunks_.find(chunk::Key(chunk::Of(c.x), chunk::Of(c.y)));
  return it == chunks_.end() ? nullptr : &(*it->second)[static_cast<std::size_t>(chunk::Offset(c))];
}

double CellLedger::SeenStamp(const Entry& e) const {
  return e.seen_s < 0.0f ? -std::numeric_limits<double>::infinity() : origin_s_ + e.seen_s;
}

float CellLedger::SinceOrigin(double stamp_s) {
  if (!have_origin_) {
    origin_s_ = stamp_s;
    have_origin_ = true;
  }
  return static_cast<float>(std::max(0.0, stamp_s - origin_s_));
}

void CellLedger::Observe(const std::vector<CellUpdate>& cells, double stamp_s) {
  const float since = SinceOrigin(stamp_s);
  for (const CellUpdate& u : cells) {
    Entry& e = At(u.cell);
    e.seen_s = std::max(e.seen_s, since);
  }
}

void CellLedger::Observe(const std::vector<CellIndex>& cells, double stamp_s) {
  const float since = SinceOrigin(stamp_s);
  for (const CellIndex c : cells) {
    Entry& e = At(c);
    e.seen_s = std::max(e.seen_s, since);
  }
}

void CellLedger::Add(CellIndex c, CellCounts delta, int sign) {
  Entry& e = At(c);
  e.hits += sign * static_cast<std::int32_t>(delta.hits);
  e.misses += sign * static_cast<std::int32_t>(delta.misses);
}

void CellLedger::Archive(const std::vector<CellUpdate>& cells) {
  for (const CellUpdate& u : cells) Add(u.cell, u.delta, +1);
}

void CellLedger::Recut(const std::vector<CellUpdate>& from, const std::vector<CellUpdate>& to) {
  auto f = from.begin();
  auto t = to.begin();
  while (f != from.end() || t != to.end()) {
    const bool take_f = t == to.end() || (f != from.end() && !RowOrder(t->cell, f->cell));
    const bool take_t = f == from.end() || (t != to.end() && !RowOrder(f->cell, t->cell));
    const CellIndex c = take_f ? f->cell : t->cell;
    const CellCounts before = take_f ? f->delta : CellCounts{};
    const CellCounts after = take_t ? t->delta : CellCounts{};
    if (before.hits != after.hits || before.misses != after.misses) {
      Add(c, before, +1);
      Add(c, after, -1);
      At(c).changed = true;
    }
    if (take_f) ++f;
    if (take_t) ++t;
  }
}

}  // namespace lifelong::slam
