#pragma once
// The one decoder of VTK XML DataArrays, shared by the .vtu and .vti readers (vtk_xml_reader.hpp).
// Internal to the input area: it includes pugixml, which only input/ links.
//
// What a DataArray holds, as VTK's vtkXMLDataParser reads it (VTK file format documentation,
// "XML File Formats"; vtkXMLWriter.cxx for the writer's side):
//   format="ascii"     whitespace-separated numbers in the element's text;
//   format="binary"    base64 in the element's text: a header, then the data;
//   format="appended"  the same header and data at byte `offset` of the <AppendedData> payload
//                      (after its '_'), raw bytes (encoding="raw") or base64 (encoding="base64").
// The header is made of words of the VTKFile's header_type (UInt32, the default, or UInt64) in
// the file's byte_order:
//   uncompressed:  [data size in bytes]
//   compressor="vtkZLibDataCompressor", "vtkLZ4DataCompressor" or "vtkLZMADataCompressor":
//                  [nblocks, block size, size of the last block (0: a full block), compressed size
//                  of block 0, ..., of block nblocks-1], then the blocks, each decompressing to
//                  block size bytes (the last to its own size): a zlib stream, a raw LZ4 block
//                  (LZ4_compress_default) or an .xz stream (lzma_easy_buffer_encode), as
//                  vtkZLibDataCompressor, vtkLZ4DataCompressor and vtkLZMADataCompressor write them.
// VTK base64-encodes the header and the data as two separate streams (each with its own '='
// padding); the decoder reads the text as a concatenation of padded base64 chunks, which reads
// that and a single stream alike.
// Types: Int8, UInt8, Int16, UInt16, Int32, UInt32, Int64, UInt64, Float32, Float64 (values are
// returned as double: exact for every float type and for integers up to 2^53).
//
// Everything a file can get wrong is one InputError "<file>: <field>: <what>": the decoder checks
// every size against the bytes present before allocating (a compressed block may claim at most
// 1032 bytes per compressed byte, zlib's largest deflate ratio, "zlib technical details"), so a
// corrupt header cannot make it allocate more than a small multiple of the file size.
#include <pugixml.hpp>

#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace rayint::vtk_xml {

enum class Compressor { none, zlib, lz4, lzma };

class Document {
 public:
  // Parses `bytes` as a VTKFile of type `type` ("UnstructuredGrid", "ImageData"). Throws InputError.
  // The AppendedData payload is read in place: `bytes` must outlive the Document.
  Document(std::string_view bytes, std::string source, const std::string& type);
  Document(const Document&) = delete;
  Document& operator=(const Document&) = delete;

  [[noreturn]] void fail(const std::string& field, const std::string& what) const;
  const std::string& source() const { return source_; }
  std::size_t source_size() const { return xml_.size() + appended_.size(); }
  pugi::xml_node dataset() const { return dataset_; }  // <UnstructuredGrid> / <ImageData>

  // The only child named `name` of `parent` at `field` (missing or repeated: an error).
  pugi::xml_node only_child(pugi::xml_node parent, const char* name, const std::string& field) const;
  // A non-negative integer attribute (missing or malformed: an error), at most `max`.
  long long count_attribute(pugi::xml_node node, const char* name, const std::string& field,
                            long long max) const;
  // `n` numbers of an attribute (e.g. "Origin"); a missing attribute gives `fallback` when it is
  // not empty, else an error.
  std::vector<double> numbers_attribute(pugi::xml_node node, const char* name, const std::string& field,
                                        std::size_t n, const std::vector<double>& fallback = {}) const;
  // NumberOfComponents of a DataArray (default 1).
  std::size_t components(pugi::xml_node array, const std::string& field) const;
  // The array's values, tuples times components of them, decoded and converted to double.
  std::vector<double> values(pugi::xml_node array, const std::string& field, std::size_t expected) const;
  // values() written where `buffer` says (e.g. straight into an array of points): buffer() is
  // called once, after the array's size has been checked against the file, and returns room for
  // `expected` doubles.
  void values_into(pugi::xml_node array, const std::string& field, std::size_t expected,
                   const std::function<double*()>& buffer) const;

 private:
  std::string source_;
  std::string xml_;             // the file with the AppendedData payload cut out
  std::string_view appended_;  // the AppendedData payload (after '_'), in the caller's bytes
  bool appended_base64_ = false;
  bool has_appended_ = false;
  bool big_endian_ = false;
  Compressor compressor_ = Compressor::none;
  std::size_t header_bytes_ = 4;
  pugi::xml_document doc_;
  pugi::xml_node dataset_;
};

// "tetra", "hexahedron", ... for VTK cell type numbers (vtkCellType.h), "other" otherwise.
const char* cell_type_name(long long type);

}  // namespace rayint::vtk_xml
