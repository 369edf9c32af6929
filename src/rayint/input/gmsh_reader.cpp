// gmsh .msh reader, MSH 2.2 and 4.1, ASCII and binary (see gmsh_reader.hpp).
#include "rayint/input/gmsh_reader.hpp"

#include <array>
#include <cstdint>
#include <cstring>
#include <map>
#include <limits>
#include <unordered_map>
#include <utility>
#include <vector>

#include "rayint/cells/cell_types.hpp"
#include "rayint/core/error.hpp"
#include "rayint/core/format.hpp"
#include "rayint/core/prefaulted.hpp"
#include "rayint/input/json_source.hpp"
#include "rayint/input/mesh_assembly.hpp"
#include "rayint/input/mesh_text.hpp"

namespace rayint {
namespace {

using mesh_text::LineCursor;

struct ElementType {
  int dim;
  int nodes;
  const char* name;
};

// gmsh's element types (reference manual, "MSH file format": elm-type), up to third order.
const ElementType* element_type(long long type) {
  static const std::map<long long, ElementType> types = {
      {1, {1, 2, "2-node line"}},          {2, {2, 3, "3-node triangle"}},
      {3, {2, 4, "4-node quadrangle"}},    {4, {3, 4, "4-node tetrahedron"}},
      {5, {3, 8, "8-node hexahedron"}},    {6, {3, 6, "6-node prism"}},
      {7, {3, 5, "5-node pyramid"}},       {8, {1, 3, "3-node line"}},
      {9, {2, 6, "6-node triangle"}},      {10, {2, 9, "9-node quadrangle"}},
      {11, {3, 10, "10-node tetrahedron"}}, {12, {3, 27, "27-node hexahedron"}},
      {13, {3, 18, "18-node prism"}},      {14, {3, 14, "14-node pyramid"}},
      {15, {0, 1, "1-node point"}},        {16, {2, 8, "8-node quadrangle"}},
      {17, {3, 20, "20-node hexahedron"}}, {18, {3, 15, "15-node prism"}},
      {19, {3, 13, "13-node pyramid"}},    {20, {2, 9, "9-node triangle"}},
      {21, {2, 10, "10-node triangle"}},   {22, {2, 12, "12-node triangle"}},
      {23, {2, 15, "15-node triangle"}},   {24, {2, 15, "15-node triangle"}},
      {25, {2, 21, "21-node triangle"}},   {26, {1, 4, "4-node line"}},
      {27, {1, 5, "5-node line"}},         {28, {1, 6, "6-node line"}},
      {29, {3, 20, "20-node tetrahedron"}}, {30, {3, 35, "35-node tetrahedron"}},
      {31, {3, 56, "56-node tetrahedron"}}};
  const auto it = types.find(type);
  return it == types.end() ? nullptr : &it->second;
}

constexpr long long kMaxTag = (1LL << 53);          // tags are read through doubles elsewhere
constexpr long long kMaxCount = 2'000'000'000;      // indices are stored as int32

// A one-component data block ($NodeData or $ElementNodeData) chosen for the scalars.
struct DataBlock {
  bool present = false;
  std::string name;
  std::vector<std::pair<long long, double>> node_values;                 // $NodeData
  std::vector<std::pair<long long, std::vector<double>>> element_values;  // $ElementNodeData
};

class MshReader {
 public:
  MshReader(std::string_view bytes, const std::string& source, const ScalarChoice& scalar,
            bool keep_cells = false)
      : c_(bytes, source, '\0'), scalar_(scalar), keep_cells_(keep_cells) {}

  TetMesh read() {
    parse();
    if (tet_corners_.empty()) fail_no_elements("no tetrahedra (type 4 or 11)");
    return finish();
  }

  // keep_cells: every linear volume element (tetrahedra, hexahedra, prisms, pyramids).
  CellMesh read_cells() {
    parse();
    if (cells_.empty()) fail_no_elements("no volume elements");
    return finish_cells();
  }

 private:
  // read() and read_cells() found none of the elements they keep.
  [[noreturn]] void fail_no_elements(const std::string& what) const {
    fail_whole("$Elements", what + "; " + std::to_string(mesh_.info.skipped_cells) + " elements of dimension 0-2 skipped");
  }

  void parse() {
    bool have_format = false, have_nodes = false, have_elements = false;
    for (;;) {
      const auto w = c_.words();
      if (w.empty()) break;
      const std::string section(w[0]);
      if (section.empty() || section[0] != '$' || section.rfind("$End", 0) == 0)
        c_.fail("(file)", "expected a section such as $Nodes, got " + field::quoted(section.substr(0, 40)));
      if (!have_format && section != "$MeshFormat") c_.fail(section, "the file must start with $MeshFormat");
      if (section == "$MeshFormat") {
        if (have_format) c_.fail(section, "given twice");
        format();
        have_format = true;
      } else if (section == "$Nodes") {
        if (have_nodes) c_.fail(section, "given twice");
        version4_ ? nodes4() : nodes2();
        have_nodes = true;
      } else if (section == "$Elements") {
        if (have_elements) c_.fail(section, "given twice");
        version4_ ? elements4() : elements2();
        have_elements = true;
      } else if (section == "$NodeData" || section == "$ElementNodeData" || section == "$ElementData") {
        data(section);
      } else {
        skip(section);
        continue;
      }
      end(section);
    }
    if (!have_format) fail_whole("$MeshFormat", "missing (not a gmsh .msh file)");
    if (!have_nodes) fail_whole("$Nodes", "missing");
    if (!have_elements) fail_whole("$Elements", "missing");
  }

  // A problem with the file as a whole (found after reading it): no line number.
  [[noreturn]] void fail_whole(const std::string& section, const std::string& what) const {
    field::fail(c_.source(), section, what);
  }

  // --- low-level reading -------------------------------------------------------------------
  template <class T>
  T bin(const std::string& field) {
    if (c_.remaining_bytes() < sizeof(T)) c_.fail(field, "binary data truncated");
    T v;
    std::memcpy(&v, c_.rest().data(), sizeof(T));
    c_.skip_bytes(sizeof(T));
    return v;
  }
  long long bin_int(const std::string& field) { return bin<std::int32_t>(field); }
  long long bin_size(const std::string& field) {
    const std::uint64_t v = bin<std::uint64_t>(field);
    if (v > static_cast<std::uint64_t>(kMaxTag)) c_.fail(field, "value " + std::to_string(v) + " out of range");
    return static_cast<long long>(v);
  }
  double bin_real(const std::string& field) {
    const double v = bin<double>(field);
    if (!std::isfinite(v)) c_.fail(field, "must be finite, got " + format_number(v));
    return v;
  }
  long long count(std::string_view w, const std::string& field) { return c_.integer(w, field, 0, kMaxCount); }
  long long tag(std::string_view w, const std::string& field) { return c_.integer(w, field, 0, kMaxTag); }

  void end(const std::string& section) {
    const std::string want = "$End" + section.substr(1);
    const auto w = c_.words();
    if (w.empty() || w[0] != want)
      c_.fail(section, "expected " + want + (w.empty() ? ", got the end of the file" : ", got " + field::quoted(std::string(w[0]).substr(0, 40))));
  }
  void skip(const std::string& section) {
    const std::string want = "$End" + section.substr(1);
    const std::string_view rest = c_.rest();
    std::size_t at = 0;
    for (;;) {  // "$EndX" at the start of a line (binary payloads may hold anything before it)
      at = rest.find(want, at);
      if (at == std::string_view::npos) c_.fail(section, "no " + want);
      if (at == 0 || rest[at - 1] == '\n') break;
      ++at;
    }
    c_.skip_bytes(at);
    c_.raw_line(section);
  }

  // --- sections ----------------------------------------------------------------------------
  void format() {
    const auto w = c_.need_words("$MeshFormat", 3, "version file-type data-size");
    const std::string v(w[0]);
    if (v == "4.1") version4_ = true;
    else if (v == "2.2" || v == "2.1" || v == "2.0") version4_ = false;
    else c_.fail("$MeshFormat", "version " + field::quoted(v.substr(0, 20)) + " is not read (MSH 2.2 and 4.1 are)");
    binary_ = c_.integer(w[1], "$MeshFormat", 0, 1) == 1;
    if (c_.integer(w[2], "$MeshFormat", 0, 64) != 8) c_.fail("$MeshFormat", "data-size must be 8");
    if (binary_) {
      if (bin<std::int32_t>("$MeshFormat") != 1)
        c_.fail("$MeshFormat", "binary file of the other byte order (only little-endian files are read)");
    }
  }

  // Node tag t gets the next point index. Tags go into dense_ (indexed by the tag) while they are
  // at least 0 and below dense_limit_ (4 slots a node of the $Nodes header, + 1024; gmsh numbers
  // nodes 1..N), else every tag moves to node_index_ (issue 33: a hash-map node per mesh node was
  // ~1,000 page faults and mallocs at 105k tets).
  std::int32_t add_node(long long t, const Vec3& p, const std::string& field) {
    const auto index = static_cast<std::int32_t>(mesh_.points.size());
    bool fresh = true;
    if (!use_map_ && t >= 0 && t < dense_limit_) {
      const auto k = static_cast<std::size_t>(t);
      if (k >= dense_.size()) dense_.resize(k + 1, -1);
      fresh = dense_[k] < 0;
      if (fresh) dense_[k] = index;
    } else {
      if (!use_map_) {
        use_map_ = true;
        for (std::size_t k = 0; k < dense_.size(); ++k)
          if (dense_[k] >= 0) node_index_.emplace(static_cast<long long>(k), dense_[k]);
        dense_ = {};
      }
      fresh = node_index_.emplace(t, index).second;
    }
    if (!fresh) c_.fail(field, "node tag " + std::to_string(t) + " given twice");
    max_node_tag_ = std::max(max_node_tag_, t);
    mesh_.points.push_back(p);
    return index;
  }

  // Room for the n nodes of the $Nodes header: the points (prefaulted: written in full) and the
  // tag table's bound.
  void reserve_nodes(long long n) {
    mesh_.points.reserve(mesh_text::reserve_bound(static_cast<std::size_t>(n), c_.remaining_bytes(), 8));
    prefault_capacity(mesh_.points);
    dense_limit_ = 4 * static_cast<long long>(mesh_.points.capacity()) + 1024;
  }

  void nodes2() {
    const std::string f = "$Nodes";
    const long long n = count(c_.need_words(f, 1, "number of nodes")[0], f);
    reserve_nodes(n);
    for (long long i = 0; i < n; ++i) {
      if (binary_) {
        const long long t = bin_int(f);
        const double x = bin_real(f), y = bin_real(f), z = bin_real(f);
        add_node(t, Vec3(x, y, z), f);
      } else {
        const auto w = c_.need_words(f, 4, "node-number x y z");
        add_node(tag(w[0], f), Vec3(c_.real(w[1], f), c_.real(w[2], f), c_.real(w[3], f)), f);
      }
    }
  }

  // The head of a v4.1 $Nodes or $Elements section (`layout`): its entity-block count and its
  // count of nodes or elements (`what`), the latter at most kMaxCount; the tag range is skipped.
  std::pair<long long, long long> section4_header(const std::string& f, const char* layout, const char* what) {
    long long blocks = 0, n = 0;
    if (binary_) {
      blocks = bin_size(f);
      n = bin_size(f);
      bin_size(f);
      bin_size(f);
    } else {
      const auto h = c_.need_words(f, 4, layout);
      blocks = count(h[0], f);
      n = count(h[1], f);
    }
    if (n > kMaxCount) c_.fail(f, std::string("too many ") + what);
    return {blocks, n};
  }

  // The header of an MSH 4 entity block of $Nodes or $Elements: entityDim entityTag <third>
  // <count> (`layout` names them). Binary: three ints and a size_t. Text: four words, entityDim
  // read (0-3) only when `read_dim`, the third in [0, third_max], the count as count().
  struct BlockHeader {
    long long dim = 0, third = 0, count = 0;
  };
  BlockHeader block_header(const std::string& f, const char* layout, bool read_dim, long long third_max) {
    BlockHeader b;
    if (binary_) {
      b.dim = bin_int(f);
      bin_int(f);
      b.third = bin_int(f);
      b.count = bin_size(f);
    } else {
      const auto h = c_.need_words(f, 4, layout);
      if (read_dim) b.dim = c_.integer(h[0], f, 0, 3);
      b.third = c_.integer(h[2], f, 0, third_max);
      b.count = count(h[3], f);
    }
    return b;
  }

  void nodes4() {
    const std::string f = "$Nodes";
    const auto [blocks, n] = section4_header(f, "numEntityBlocks numNodes minNodeTag maxNodeTag", "nodes");
    reserve_nodes(n);
    long long seen = 0;
    for (long long b = 0; b < blocks; ++b) {
      const BlockHeader h = block_header(f, "entityDim entityTag parametric numNodesInBlock", true, 1);
      const long long dim = h.dim, parametric = h.third, in_block = h.count;
      if (dim < 0 || dim > 3) c_.fail(f, "entityDim must be 0-3");
      if (in_block > n - seen) c_.fail(f, "more nodes in the blocks than the header's " + std::to_string(n));
      seen += in_block;
      const std::size_t coords = 3 + (parametric != 0 ? static_cast<std::size_t>(dim) : 0);
      std::vector<long long> tags;
      tags.reserve(mesh_text::reserve_bound(static_cast<std::size_t>(in_block), c_.remaining_bytes(), 1));
      for (long long i = 0; i < in_block; ++i)
        tags.push_back(binary_ ? bin_size(f) : tag(c_.need_words(f, 1, "nodeTag")[0], f));
      for (long long i = 0; i < in_block; ++i) {
        std::array<double, 3> x{};
        if (binary_) {
          for (std::size_t k = 0; k < coords; ++k) {
            const double v = bin_real(f);
            if (k < 3) x[k] = v;
          }
        } else {
          const auto w = c_.need_words(f, coords, "x y z [u v w]");
          for (std::size_t k = 0; k < 3; ++k) x[k] = c_.real(w[k], f);
        }
        add_node(tags[static_cast<std::size_t>(i)], Vec3(x[0], x[1], x[2]), f);
      }
    }
    if (seen != n) c_.fail(f, "the blocks hold " + std::to_string(seen) + " nodes, the header says " + std::to_string(n));
  }

  // One element, through the cell-type table (cells/cell_types.hpp): tets are kept (nodes by
  // tag, resolved in finish()), dimensions 0-2 skipped and counted, other volume elements refused.
  // What element() needs of an element type, looked up once per type in a row (a block of a
  // binary or v4.1 file has one type; issue 33: the lookups and the label were per element).
  struct TypeCache {
    long long type = -1;
    const ElementType* et = nullptr;
    const CellTypeInfo* row = nullptr;
    long* count = nullptr;    // mesh_.info.cells_by_type[label] (std::map: the address is stable)
    long* skipped = nullptr;  // mesh_.info.skipped_by_type[label], for dimensions 0-2
  };
  const TypeCache& type_of(long long type, const std::string& f) {
    if (type == type_cache_.type) return type_cache_;
    const ElementType* et = element_type(type);
    if (!et) c_.fail(f, "unknown element type " + std::to_string(type));
    const CellTypeInfo* row = cell_type_from_gmsh(type);
    const std::string label = row != nullptr ? std::string(row->name) : std::string("gmsh ") + et->name;
    type_cache_ = TypeCache{type, et, row, &mesh_.info.cells_by_type[label],
                            et->dim < 3 ? &mesh_.info.skipped_by_type[label] : nullptr};
    return type_cache_;
  }

  void element(long long t, long long type, const std::vector<long long>& nodes, const std::string& f) {
    const TypeCache& tc = type_of(type, f);
    const ElementType* et = tc.et;
    const CellTypeInfo* row = tc.row;
    ++*tc.count;
    if (et->dim < 3) {
      ++mesh_.info.skipped_cells;
      ++*tc.skipped;
      return;
    }
    if (row == nullptr)  // a volume element without a VTK counterpart in the table (cells/cell_types.hpp)
      c_.fail(f, "element type " + std::to_string(type) + " (" + et->name + ") is not supported" +
                     (type == 14 ? ": VTK has no 14-node pyramid (its quadratic pyramid has 13 nodes; gmsh writes those, "
                                   "type 19, with Mesh.SecondOrderIncomplete = 1)"
                                 : "; gmsh types 4-7, 11-13 and 17-19 are integrated"));
    if (keep_cells_ && (row->support == CellSupport::Traversed || row->support == CellSupport::CellPath ||
                        row->support == CellSupport::Quadratic || row->support == CellSupport::Isoparametric)) {
      cells_.push_back({t, row, {}});
      for (int k = 0; k < row->nodes; ++k) cells_.back().nodes.push_back(nodes[static_cast<std::size_t>(k)]);
      return;
    }
    if (keep_cells_ || (row->support != CellSupport::Traversed && row->support != CellSupport::Quadratic))
      c_.fail(f, unsupported_cell_message(row->vtk_id) + " (gmsh element type " + std::to_string(type) + ")");
    tet_tags_.push_back(t);
    // VTK's node order (the table's permutation). Mid-edge tags only once a 10-node tet comes
    // (the linear ones before it get kNoNode rows then): a linear mesh holds 4 tags a tet.
    std::array<long long, 4> v{};
    for (std::size_t k = 0; k < 4; ++k) v[k] = nodes[static_cast<std::size_t>(row->gmsh_to_vtk[k])];
    tet_corners_.push_back(v);
    if (row->nodes == 10) {
      if (!quadratic_) tet_edges_.assign(tet_corners_.size() - 1, kLinearEdges);
      quadratic_ = true;
      std::array<long long, 6>& e = tet_edges_.emplace_back();
      for (std::size_t k = 0; k < 6; ++k) e[k] = nodes[static_cast<std::size_t>(row->gmsh_to_vtk[4 + k])];
    } else if (quadratic_) {
      tet_edges_.push_back(kLinearEdges);
    }
  }
  // Node tag k (VTK's order, 0-9) of tet i; kNoNode for a linear tet's mid-edge nodes.
  long long tet_node(std::size_t i, std::size_t k) const {
    return k < 4 ? tet_corners_[i][k] : quadratic_ ? tet_edges_[i][k - 4] : kNoNode;
  }

  // Room for n tets (as many as the header's elements), prefaulted; none in keep_cells mode.
  void reserve_elements(long long n) {
    if (keep_cells_) return;
    const std::size_t bound = mesh_text::reserve_bound(static_cast<std::size_t>(n), c_.remaining_bytes(), 12);
    tet_corners_.reserve(bound);
    tet_tags_.reserve(bound);
    prefault_capacity(tet_corners_);
    prefault_capacity(tet_tags_);
  }

  void elements2() {
    const std::string f = "$Elements";
    const long long n = count(c_.need_words(f, 1, "number of elements")[0], f);
    reserve_elements(n);
    std::vector<long long> nodes;
    if (binary_) {
      long long done = 0;
      while (done < n) {
        const long long type = bin_int(f), in_block = bin_int(f), ntags = bin_int(f);
        const ElementType* et = element_type(type);
        if (!et) c_.fail(f, "unknown element type " + std::to_string(type));
        if (in_block < 1 || in_block > n - done || ntags < 0 || ntags > 1000)
          c_.fail(f, "element block header out of range");
        for (long long i = 0; i < in_block; ++i) {
          const long long t = bin_int(f);
          for (long long k = 0; k < ntags; ++k) bin_int(f);
          nodes.assign(static_cast<std::size_t>(et->nodes), 0);
          for (auto& x : nodes) x = bin_int(f);
          element(t, type, nodes, f);
        }
        done += in_block;
      }
      return;
    }
    for (long long i = 0; i < n; ++i) {
      const auto w = c_.need_words(f, 3, "elm-number elm-type number-of-tags ...");
      const long long t = tag(w[0], f), type = c_.integer(w[1], f, 0, 100000);
      const long long ntags = c_.integer(w[2], f, 0, 1000);
      const ElementType* et = element_type(type);
      if (!et) c_.fail(f, "unknown element type " + std::to_string(type));
      const std::size_t want = 3 + static_cast<std::size_t>(ntags) + static_cast<std::size_t>(et->nodes);
      if (w.size() != want)
        c_.fail(f, "element " + std::to_string(t) + ": " + std::to_string(w.size()) + " numbers, a " + et->name +
                       " with " + std::to_string(ntags) + " tags needs " + std::to_string(want));
      nodes.clear();
      for (std::size_t k = 3 + static_cast<std::size_t>(ntags); k < w.size(); ++k) nodes.push_back(tag(w[k], f));
      element(t, type, nodes, f);
    }
  }

  void elements4() {
    const std::string f = "$Elements";
    const auto [blocks, n] = section4_header(f, "numEntityBlocks numElements minElementTag maxElementTag", "elements");
    reserve_elements(n);
    long long seen = 0;
    std::vector<long long> nodes;
    for (long long b = 0; b < blocks; ++b) {
      const BlockHeader h = block_header(f, "entityDim entityTag elementType numElementsInBlock", false, 100000);
      const long long type = h.third, in_block = h.count;
      const ElementType* et = element_type(type);
      if (!et) c_.fail(f, "unknown element type " + std::to_string(type));
      if (in_block > n - seen) c_.fail(f, "more elements in the blocks than the header's " + std::to_string(n));
      seen += in_block;
      if (binary_) {
        // Each element's (1 + nodes) size_t words read in one go (the cursor then moves past them,
        // as bin_size would have): each value as bin_size checks it (at most kMaxTag).
        const auto words = static_cast<std::size_t>(1 + et->nodes);
        nodes.assign(static_cast<std::size_t>(et->nodes), 0);
        for (long long i = 0; i < in_block; ++i) {
          if (c_.remaining_bytes() < 8 * words) c_.fail(f, "binary data truncated");
          const char* p = c_.rest().data();
          long long t = 0;
          for (std::size_t w = 0; w < words; ++w, p += 8) {
            std::uint64_t v = 0;
            std::memcpy(&v, p, 8);
            if (v > static_cast<std::uint64_t>(kMaxTag)) c_.fail(f, "value " + std::to_string(v) + " out of range");
            (w == 0 ? t : nodes[w - 1]) = static_cast<long long>(v);
          }
          c_.skip_bytes(8 * words);
          element(t, type, nodes, f);
        }
        continue;
      }
      for (long long i = 0; i < in_block; ++i) {
        nodes.assign(static_cast<std::size_t>(et->nodes), 0);
        const auto w = c_.need_words(f, 1 + nodes.size(), "elementTag nodeTag...");
        if (w.size() != 1 + nodes.size())
          c_.fail(f, std::to_string(w.size() - 1) + " node tags for a " + et->name);
        const long long t = tag(w[0], f);
        for (std::size_t k = 0; k < nodes.size(); ++k) nodes[k] = tag(w[k + 1], f);
        element(t, type, nodes, f);
      }
    }
    if (seen != n) c_.fail(f, "the blocks hold " + std::to_string(seen) + " elements, the header says " + std::to_string(n));
  }

  void data(const std::string& f) {
    const bool per_element = f == "$ElementNodeData";
    const bool per_cell = f == "$ElementData";
    const long long nstrings = c_.integer(c_.need_words(f, 1, "numStringTags")[0], f, 0, 1000);
    std::string name;
    for (long long i = 0; i < nstrings; ++i) {
      std::string s(c_.raw_line(f));
      while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.pop_back();
      if (s.size() >= 2 && s.front() == '"' && s.back() == '"') s = s.substr(1, s.size() - 2);
      if (i == 0) name = s;
    }
    const long long nreals = c_.integer(c_.need_words(f, 1, "numRealTags")[0], f, 0, 1000);
    for (long long i = 0; i < nreals; ++i) c_.need_words(f, 1, "real tag");
    const long long nints = c_.integer(c_.need_words(f, 1, "numIntegerTags")[0], f, 0, 1000);
    if (nints < 3) c_.fail(f, "needs 3 integer tags (time step, components, entities)");
    std::array<long long, 3> ints{};
    for (long long i = 0; i < nints; ++i) {
      const long long v = c_.integer(c_.need_words(f, 1, "integer tag")[0], f, -kMaxCount, kMaxCount);
      if (i < 3) ints[static_cast<std::size_t>(i)] = v;
    }
    const long long comps = ints[1], n = ints[2];
    if (comps < 1 || comps > 9) c_.fail(f, "number of components must be 1-9, got " + std::to_string(comps));
    if (n < 0) c_.fail(f, "negative number of entities");
    mesh_.info.arrays.push_back({name, per_cell ? "cell" : per_element ? "point (per element)" : "point", comps,
                                 is_marker_array(name)});
    const bool wanted_name = scalar_.name.empty() ? !is_marker_array(name) : name == scalar_.name;
    DataBlock& slot = per_element ? element_data_ : per_cell ? cell_data_ : node_data_;
    const bool take = wanted_name && comps == 1 && !slot.present;
    if (take) {
      slot.present = true;
      slot.name = name;
    }
    for (long long i = 0; i < n; ++i) {
      long long t = 0, per = 1;
      std::vector<double> values;
      // gmsh's "Save View" of a built-in-kernel geometry writes entries with node tag -1 for
      // geometry points that are not mesh nodes (e.g. a circle's centre); gmsh itself ignores
      // them when it reads the file back. So does rayint, counting them (skipped_node_data).
      bool orphan = false;
      if (binary_) {
        t = bin_int(f);
        orphan = !per_element && !per_cell && t == -1;
        if (per_element) per = bin_int(f);
        if (per < 0 || per > 1000) c_.fail(f, "nodes per element out of range");
        for (long long k = 0; k < per * comps; ++k) values.push_back(bin_real(f));
      } else {
        const auto w = c_.need_words(f, 2, "tag value...");
        orphan = !per_element && !per_cell && w[0] == "-1";
        t = orphan ? -1 : tag(w[0], f);
        std::size_t k0 = 1;
        if (per_element) {
          per = c_.integer(w[1], f, 0, 1000);
          k0 = 2;
        }
        if (w.size() != k0 + static_cast<std::size_t>(per * comps))
          c_.fail(f, "entity " + std::to_string(t) + ": " + std::to_string(w.size() - k0) + " values, expected " +
                         std::to_string(per * comps));
        for (std::size_t k = k0; k < w.size(); ++k) values.push_back(c_.real(w[k], f));
      }
      if (!take) continue;
      if (orphan) {
        ++mesh_.info.skipped_node_data;
        continue;
      }
      if (per_element) slot.element_values.emplace_back(t, std::move(values));
      else slot.node_values.emplace_back(t, values[0]);  // per node, or per element for $ElementData
    }
  }

  // --- assembling ----------------------------------------------------------------------------
  // A $NodeData entry of an MSH 4.1 file for a node gmsh did not save (counted, skipped). gmsh's
  // PViewDataGModel::writeMSH writes each value with its node's number in the model (getNum() for
  // MSH >= 3; getIndex() for 2.2, which is -1 for a node not saved: the tag -1 case above), and
  // gmsh numbers the nodes of the saved elements first when it saves a mesh, so a node it did not
  // write (a built-in-kernel geometry point such as a circle's centre, which Plugin(NewView) gives
  // a value) has a number past the last one in $Nodes. gmsh reads such entries back and never
  // draws them; rayint skips them and counts them (MeshInfo::skipped_node_data). A tag inside
  // $Nodes' range that is missing is still refused: the file then contradicts itself.
  bool unsaved_node(long long t, MeshFileInfo& info) {
    if (!version4_ || t <= max_node_tag_ || node_index_.count(t)) return false;
    ++info.skipped_node_data;
    return true;
  }

  // The point index of node tag t, -1 when $Nodes has no such tag: through a table indexed by
  // the tag when the tags are dense enough (add_node), else through node_index_.
  std::int32_t find_node(long long t) const {
    if (!use_map_) return t >= 0 && static_cast<unsigned long long>(t) < dense_.size() ? dense_[static_cast<std::size_t>(t)] : -1;
    const auto it = node_index_.find(t);
    return it == node_index_.end() ? -1 : it->second;
  }

  std::int32_t node(long long t, const std::string& field) {
    const std::int32_t i = find_node(t);
    if (i < 0) fail_whole(field, "node tag " + std::to_string(t) + " is not in $Nodes");
    return i;
  }
  // node() for a node of element `element_tag` (the field is named only when it fails).
  std::int32_t element_node(long long t, long long element_tag) {
    const std::int32_t i = find_node(t);
    if (i < 0) node(t, "$Elements (element " + std::to_string(element_tag) + ")");
    return i;
  }

  // What finish() and finish_cells() say when no data block gives the scalar.
  std::string no_scalar_text() const {
    return scalar_.name.empty()
               ? "no one-component $NodeData, $ElementNodeData or $ElementData that is not a marker"
               : "no one-component $NodeData, $ElementNodeData or $ElementData named " +
                     field::quoted(scalar_.name);
  }

  // $NodeData into value (have[i] = 1 for each point given one); nodes not saved are skipped.
  void node_data_values(MeshFileInfo& info, std::vector<double>& value, std::vector<char>& have) {
    for (const auto& [t, v] : node_data_.node_values) {
      if (unsaved_node(t, info)) continue;
      const auto i = static_cast<std::size_t>(node(t, "$NodeData"));
      value[i] = v;
      have[i] = 1;
    }
  }

  // One $ElementNodeData value v for point i; a point given two different values is refused,
  // naming it as `noun` + `label` ("node <tag>" or "point <index>").
  void element_node_value(std::vector<double>& value, std::vector<char>& have, std::size_t i, double v,
                          const char* noun, long long label) const {
    if (have[i] && value[i] != v)
      fail_whole("$ElementNodeData", noun + std::to_string(label) + " has two values (" + format_number(value[i]) +
                                         " and " + format_number(v) + "): the field is not continuous");
    value[i] = v;
    have[i] = 1;
  }

  TetMesh finish() {
    mesh_.tets.reserve(tet_corners_.size());
    mesh_.info.cell_ids.reserve(tet_corners_.size());
    prefault_capacity(mesh_.tets);
    prefault_capacity(mesh_.info.cell_ids);
    if (quadratic_) mesh_.edge_nodes.reserve(tet_corners_.size());
    for (std::size_t i = 0; i < tet_corners_.size(); ++i) {
      std::array<std::int32_t, 4> t{};
      for (std::size_t k = 0; k < 4; ++k) t[k] = element_node(tet_corners_[i][k], tet_tags_[i]);
      mesh_.tets.push_back(t);
      mesh_.info.cell_ids.push_back(tet_tags_[i]);
      if (quadratic_) {
        std::array<std::int32_t, 6>& e = mesh_.edge_nodes.emplace_back();
        for (std::size_t k = 0; k < 6; ++k)
          e[k] = tet_edges_[i][k] == kNoNode ? -1 : element_node(tet_edges_[i][k], tet_tags_[i]);
      }
    }
    std::vector<double> value(mesh_.points.size(), 0.0);
    std::vector<char> have(mesh_.points.size(), 0);
    if (node_data_.present) {
      node_data_values(mesh_.info, value, have);
    } else if (element_data_.present) {
      std::unordered_map<long long, std::size_t> tet_of;
      for (std::size_t i = 0; i < tet_tags_.size(); ++i) tet_of.emplace(tet_tags_[i], i);
      for (const auto& [t, vs] : element_data_.element_values) {
        const auto it = tet_of.find(t);
        if (it == tet_of.end()) continue;  // data on a point, line or triangle element
        const std::size_t nodes = tet_node(it->second, 4) == kNoNode ? 4 : 10;
        if (vs.size() != nodes)
          fail_whole("$ElementNodeData", "element " + std::to_string(t) + " (a tetrahedron) has " +
                                          std::to_string(vs.size()) + " values, expected " + std::to_string(nodes));
        const CellTypeInfo* row = cell_type_from_vtk(nodes == 4 ? kVtkTetra : kVtkQuadraticTetra);
        for (std::size_t k = 0; k < nodes; ++k) {
          // vtk node k is gmsh node gmsh_to_vtk[k]: its value is vs[gmsh_to_vtk[k]].
          const auto i = static_cast<std::size_t>(k < 4 ? mesh_.tets[it->second][k] : mesh_.edge_nodes[it->second][k - 4]);
          element_node_value(value, have, i, vs[static_cast<std::size_t>(row->gmsh_to_vtk[k])], "node ",
                             tet_node(it->second, k));
        }
      }
    } else if (cell_data_.present) {
      // $ElementData: one value per element, constant over the tetrahedron (cell data).
      std::unordered_map<long long, double> by_tag;
      for (const auto& [t, v] : cell_data_.node_values) by_tag[t] = v;
      for (std::size_t i = 0; i < tet_tags_.size(); ++i) {
        const auto it = by_tag.find(tet_tags_[i]);
        if (it == by_tag.end())
          fail_whole("$ElementData", "no value for element " + std::to_string(tet_tags_[i]) + " (a tetrahedron)");
        mesh_.cell_scalars.push_back(it->second);
      }
      mesh_.info.scalar = cell_data_.name;
      mesh_.info.scalar_association = "cell";
      if (scalar_.cell_to_point) {
        mesh_.scalars = cell_to_point_average(mesh_);
        mesh_.cell_scalars.clear();
        mesh_.info.scalar_association = "cell averaged to points";
      }
      validate_tet_mesh_structure(mesh_, c_.source(), MeshFieldNames{"$Nodes", "$ElementData", "$Elements"});
      return std::move(mesh_);
    } else {
      fail_whole("$NodeData", no_scalar_text() + " (one scalar per node is required; arrays: " + list_arrays(mesh_.info.arrays) + ")");
    }
    mesh_.info.scalar = node_data_.present ? node_data_.name : element_data_.name;
    // Every node of a tet has a value (corners of all tets first, then the mid-edge nodes: the
    // first one without names the point).
    const auto need_value = [&](std::int32_t i) {
      if (i >= 0 && !have[static_cast<std::size_t>(i)])
        fail_whole(node_data_.present ? "$NodeData" : "$ElementNodeData",
                   "no value for a node of a tetrahedron (point " + std::to_string(i) + ")");
    };
    for (const auto& t : mesh_.tets)
      for (const std::int32_t i : t) need_value(i);
    for (const auto& e : mesh_.edge_nodes)
      for (const std::int32_t i : e) need_value(i);
    mesh_.scalars = std::move(value);
    validate_tet_mesh_structure(mesh_, c_.source(), MeshFieldNames{"$Nodes", "$NodeData", "$Elements"});
    return std::move(mesh_);
  }

  // The CellMesh of keep_cells mode. Node tags are permuted to VTK's order here, and
  // $ElementNodeData values (given in gmsh's node order) with the same permutation, so a node is
  // never separated from its value.
  CellMesh finish_cells() {
    CellMesh m;
    m.points = std::move(mesh_.points);
    m.info = std::move(mesh_.info);
    for (const RawCell& rc : cells_) {
      const std::string where = "$Elements (element " + std::to_string(rc.tag) + ")";
      for (int k = 0; k < rc.row->nodes; ++k)
        m.connectivity.push_back(node(rc.nodes[static_cast<std::size_t>(rc.row->gmsh_to_vtk[static_cast<std::size_t>(k)])], where));
      m.types.push_back(static_cast<MeshCellType>(rc.row->vtk_id));
      m.offsets.push_back(static_cast<std::uint32_t>(m.connectivity.size()));
      m.info.cell_ids.push_back(rc.tag);
    }
    std::vector<double> value(m.points.size(), 0.0);
    std::vector<char> have(m.points.size(), 0);
    std::string data_field = "$NodeData";
    if (node_data_.present) {
      node_data_values(m.info, value, have);
      m.info.scalar = node_data_.name;
    } else if (element_data_.present) {
      data_field = "$ElementNodeData";
      std::unordered_map<long long, std::size_t> cell_of;
      for (std::size_t i = 0; i < cells_.size(); ++i) cell_of.emplace(cells_[i].tag, i);
      for (const auto& [t, vs] : element_data_.element_values) {
        const auto it = cell_of.find(t);
        if (it == cell_of.end()) continue;  // data on a point, line or surface element
        const RawCell& rc = cells_[it->second];
        if (vs.size() != static_cast<std::size_t>(rc.row->nodes))
          fail_whole("$ElementNodeData", "element " + std::to_string(t) + " (a " + rc.row->name + ") has " +
                                             std::to_string(vs.size()) + " values, expected " + std::to_string(rc.row->nodes));
        const std::int32_t* p = m.connectivity.data() + m.offsets[it->second];
        for (std::size_t k = 0; k < vs.size(); ++k) {
          const auto i = static_cast<std::size_t>(p[k]);
          element_node_value(value, have, i, vs[static_cast<std::size_t>(rc.row->gmsh_to_vtk[k])], "point ",
                             static_cast<long long>(i));
        }
      }
      m.info.scalar = element_data_.name;
    } else if (cell_data_.present) {
      std::unordered_map<long long, double> by_tag;
      for (const auto& [t, v] : cell_data_.node_values) by_tag[t] = v;
      for (const RawCell& rc : cells_) {
        const auto it = by_tag.find(rc.tag);
        if (it == by_tag.end())
          fail_whole("$ElementData", "no value for element " + std::to_string(rc.tag) + " (a " + rc.row->name + ")");
        m.cell_scalars.push_back(it->second);
      }
      m.info.scalar = cell_data_.name;
      m.info.scalar_association = "cell";
      if (scalar_.cell_to_point) {
        // vtkCellDataToPointData over the volume cells: plain average at each point.
        std::vector<long> count(m.points.size(), 0);
        for (std::size_t c = 0; c < m.cell_count(); ++c)
          for (std::size_t k = 0; k < m.nodes_of(c); ++k) {
            const auto i = static_cast<std::size_t>(m.cell(c)[k]);
            value[i] += m.cell_scalars[c];
            ++count[i];
          }
        for (std::size_t i = 0; i < value.size(); ++i)
          if (count[i] > 0) value[i] /= static_cast<double>(count[i]);
        m.scalars = std::move(value);
        m.cell_scalars.clear();
        m.info.scalar_association = "cell averaged to points";
      }
      validate_cell_mesh_structure(m, c_.source(), MeshFieldNames{"$Nodes", "$ElementData", "$Elements"});
      return m;
    } else {
      fail_whole("$NodeData", no_scalar_text() + " (one scalar per node is required; arrays: " + list_arrays(m.info.arrays) + ")");
    }
    for (const std::int32_t i : m.connectivity)
      if (!have[static_cast<std::size_t>(i)])
        fail_whole(data_field, "no value for a node of a volume element (point " + std::to_string(i) + ")");
    m.scalars = std::move(value);
    validate_cell_mesh_structure(m, c_.source(), MeshFieldNames{"$Nodes", data_field, "$Elements"});
    return m;
  }

  struct RawCell {
    long long tag;
    const CellTypeInfo* row;
    std::vector<long long> nodes;  // node tags, gmsh's order
  };

  LineCursor c_;
  ScalarChoice scalar_;  // the array to take, and whether a cell field becomes point data
  bool keep_cells_ = false;
  std::vector<RawCell> cells_;
  bool version4_ = false, binary_ = false;
  long long max_node_tag_ = 0;  // the largest tag in $Nodes
  TetMesh mesh_;
  std::unordered_map<long long, std::int32_t> node_index_;
  std::vector<long long> tet_tags_;
  static constexpr long long kNoNode = std::numeric_limits<long long>::min();
  std::vector<std::array<long long, 4>> tet_corners_;  // node tags of the corners, VTK's order
  std::vector<std::array<long long, 6>> tet_edges_;    // mid-edge node tags, VTK's order (only when quadratic_)
  static constexpr std::array<long long, 6> kLinearEdges{kNoNode, kNoNode, kNoNode, kNoNode, kNoNode, kNoNode};
  bool quadratic_ = false;                             // some tet has 10 nodes
  TypeCache type_cache_;
  std::vector<std::int32_t> dense_;  // node tag -> point index, -1: none (add_node, find_node)
  long long dense_limit_ = 1024;     // tags below it go into dense_ (reserve_nodes)
  bool use_map_ = false;             // the tags are in node_index_, not dense_
  DataBlock node_data_, element_data_, cell_data_;
};

}  // namespace

TetMesh parse_gmsh(std::string_view bytes, const std::string& source, const ScalarChoice& scalar) {
  return MshReader(bytes, source, scalar).read();
}

TetMesh read_gmsh(const std::string& path, const ScalarChoice& scalar) {
  return parse_gmsh(json_source::read_big_file(path), path, scalar);
}

CellMesh parse_gmsh_cells(std::string_view bytes, const std::string& source, const ScalarChoice& scalar) {
  return MshReader(bytes, source, scalar, true).read_cells();
}

CellMesh read_gmsh_cells(const std::string& path, const ScalarChoice& scalar) {
  return parse_gmsh_cells(json_source::read_big_file(path), path, scalar);
}

}  // namespace rayint
