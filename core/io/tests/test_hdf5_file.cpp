// H5File: round trips, extendible series, attributes, and errors that name file and object.
#include "core/base/error.hpp"
#include "core/io/hdf5_file.hpp"
#include "core/testing/temp_dir.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace fs = std::filesystem;
using tmlab::H5File;

namespace {

class Hdf5FileTest : public tmlab::testing::TempDirTest {
 protected:
  std::string file(const std::string& name) const { return (dir_ / name).string(); }
};

TEST_F(Hdf5FileTest, RoundTripDoubleAndIntWithIntermediateGroups) {
  const std::vector<double> u = {0.0, 1.5, -2.25, 3e-12, 4.0, 5.0};
  const std::vector<std::int32_t> tets = {0, 1, 2, 3, 1, 2, 3, 4};
  const std::vector<std::int64_t> big = {1LL << 40, -7};
  {
    H5File f = H5File::create(file("a.h5"));
    f.write("/steps/000012/u", u, {2, 3});
    f.write("mesh/topology", tets, {2, 4});
    f.write("/big", big, {2});
    f.close();
  }
  H5File f = H5File::open_read(file("a.h5"));
  H5File::Dims dims;
  EXPECT_EQ(f.read_double("/steps/000012/u", &dims), u);
  EXPECT_EQ(dims, (H5File::Dims{2, 3}));
  EXPECT_EQ(f.read_int32("/mesh/topology", &dims), tets);
  EXPECT_EQ(dims, (H5File::Dims{2, 4}));
  EXPECT_EQ(f.read_int64("/big"), big);
  EXPECT_EQ(f.type("/steps/000012/u"), tmlab::H5Type::Float64);
  EXPECT_EQ(f.type("/mesh/topology"), tmlab::H5Type::Int32);
  EXPECT_EQ(f.type("/big"), tmlab::H5Type::Int64);
  EXPECT_TRUE(f.exists("/steps/000012"));
  EXPECT_TRUE(f.exists("/steps/000012/u"));
  EXPECT_FALSE(f.exists("/steps/000013/u"));
  EXPECT_FALSE(f.exists("/big/not_a_group"));
  EXPECT_EQ(f.list("/"), (std::vector<std::string>{"big", "mesh", "steps"}));
  // Converting reads.
  const auto as_double = f.read_double("/mesh/topology");
  EXPECT_EQ(as_double[7], 4.0);
}

TEST_F(Hdf5FileTest, RewritingReplacesDatasetAndEmptyDatasetsWork) {
  H5File f = H5File::create(file("b.h5"));
  f.write("/x", std::vector<double>{1, 2, 3}, {3});
  f.write("/x", std::vector<double>{9, 8}, {1, 2});
  EXPECT_EQ(f.read_double("/x"), (std::vector<double>{9, 8}));
  EXPECT_EQ(f.dims("/x"), (H5File::Dims{1, 2}));
  f.write("/empty", std::vector<double>{}, {0, 3});
  EXPECT_TRUE(f.read_double("/empty").empty());
  EXPECT_EQ(f.dims("/empty"), (H5File::Dims{0, 3}));
}

TEST_F(Hdf5FileTest, AppendRowsAndValues) {
  {
    H5File f = H5File::create(file("series.h5"));
    for (int k = 0; k < 5000; ++k) {
      f.append("/series/time", 0.01 * k);
      f.append_row("/series/energy", {1.0 * k, 2.0 * k, -1.0 * k});
    }
  }  // destructor closes
  H5File f = H5File::open_read(file("series.h5"));
  H5File::Dims dims;
  const auto t = f.read_double("/series/time", &dims);
  ASSERT_EQ(dims, (H5File::Dims{5000}));
  EXPECT_DOUBLE_EQ(t[4999], 49.99);
  const auto e = f.read_double("/series/energy", &dims);
  ASSERT_EQ(dims, (H5File::Dims{5000, 3}));
  EXPECT_EQ(e[3 * 17 + 0], 17.0);
  EXPECT_EQ(e[3 * 17 + 2], -17.0);
}

TEST_F(Hdf5FileTest, AppendRowOfWrongWidthThrows) {
  H5File f = H5File::create(file("w.h5"));
  f.append_row("/r", {1.0, 2.0});
  EXPECT_THROW(f.append_row("/r", {1.0, 2.0, 3.0}), tmlab::Error);
  EXPECT_THROW(f.append_row("/q", {}), tmlab::Error);
  f.write("/fixed", std::vector<double>{1.0}, {1});
  EXPECT_THROW(f.append("/fixed", 2.0), tmlab::Error);  // not extendible
}

TEST_F(Hdf5FileTest, Attributes) {
  H5File f = H5File::create(file("attr.h5"));
  f.append("/series/time", 0.0);
  f.set_attribute("/series/time", "unit", "s");
  f.set_attribute("/series/time", "unit", std::string("ms"));  // replaced
  f.set_attribute("/", "dt", 1e-3);
  f.set_attribute("/", "steps", 120);
  f.set_attribute("/", "empty", "");
  EXPECT_EQ(f.string_attribute("/series/time", "unit"), "ms");
  EXPECT_DOUBLE_EQ(f.double_attribute("/", "dt"), 1e-3);
  EXPECT_EQ(f.int_attribute("/", "steps"), 120);
  EXPECT_EQ(f.string_attribute("/", "empty"), "");
  EXPECT_TRUE(f.has_attribute("/", "dt"));
  EXPECT_FALSE(f.has_attribute("/", "nope"));
  EXPECT_THROW(f.string_attribute("/", "nope"), tmlab::Error);
  EXPECT_THROW(f.double_attribute("/series/time", "unit"), tmlab::Error);
  EXPECT_THROW(f.set_attribute("/missing", "unit", "s"), tmlab::Error);
}

TEST_F(Hdf5FileTest, ErrorsNameFileAndObject) {
  const std::string missing = file("no/such/dir/x.h5");
  try {
    H5File::create(missing);
    FAIL() << "expected tmlab::Error";
  } catch (const tmlab::Error& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
  EXPECT_THROW(H5File::open_read(file("absent.h5")), tmlab::Error);

  H5File f = H5File::create(file("e.h5"));
  try {
    f.read_double("/steps/000001/u");
    FAIL() << "expected tmlab::Error";
  } catch (const tmlab::Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("e.h5"), std::string::npos) << msg;
    EXPECT_NE(msg.find("/steps/000001/u"), std::string::npos) << msg;
  }
  EXPECT_THROW(f.write("/a", std::vector<double>{1, 2, 3}, {2, 2}), tmlab::Error);
  f.write("/a", std::vector<double>{1, 2}, {2});
  // A dataset cannot be a group: the HDF5 failure becomes a message naming the object.
  try {
    f.write("/a/b", std::vector<double>{1}, {1});
    FAIL() << "expected tmlab::Error";
  } catch (const tmlab::Error& e) {
    EXPECT_NE(std::string(e.what()).find("/a"), std::string::npos) << e.what();
  }
  f.close();
  EXPECT_THROW(f.read_double("/a"), tmlab::Error);

  // Reading a file that is not HDF5.
  {
    std::FILE* g = std::fopen(file("text.h5").c_str(), "w");
    std::fputs("hello", g);
    std::fclose(g);
  }
  EXPECT_THROW(H5File::open_read(file("text.h5")), tmlab::Error);
}

TEST_F(Hdf5FileTest, MoveTransfersOwnership) {
  H5File a = H5File::create(file("m.h5"));
  H5File b = std::move(a);
  EXPECT_FALSE(a.is_open());  // NOLINT(bugprone-use-after-move)
  b.write("/x", std::vector<double>{1}, {1});
  b.close();
  b.close();  // idempotent
  EXPECT_EQ(H5File::open_read(file("m.h5")).read_double("/x"), (std::vector<double>{1}));
}

}  // namespace
