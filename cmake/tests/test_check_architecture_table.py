#!/usr/bin/env python3
"""Unit tests of cmake/check_architecture_table.py (ctest architecture_table_self_test)."""
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import check_architecture_table as cat  # noqa: E402

TABLE = """# Architecture
## Modules (CMake targets)
| target | folder | depends on | holds |
|---|---|---|---|
| `tmlab::base` | `core/base/` | | errors |
| `tmlab::mesh` | `core/mesh/` | base, Eigen | meshes |
| `tmlab::io` | `core/io/` | mesh (privately HDF5 (OpenMPI flavour), `tmlab::base`) | files |
| `tmlab::reference_fem` | `reference_fem/dealii/` | mesh, deal.II 9.4 | the reference |
| `tmlab::checks` | `verification/checks/` | mesh (privately reference_fem (when built)) | checks |
## Where each capability goes
| `tmlab::nothing` | x | y | z |
"""

GRAPH = {
    "tmlab_base": {"type": "STATIC_LIBRARY", "link": ["tmlab::options"],
                   "interface": ["$<LINK_ONLY:tmlab::options>"]},
    "tmlab_mesh": {"type": "STATIC_LIBRARY", "link": ["tmlab::base", "Eigen3::Eigen", "tmlab::options"],
                   "interface": ["tmlab::base", "Eigen3::Eigen", "$<LINK_ONLY:tmlab::options>"]},
    "tmlab_io": {"type": "STATIC_LIBRARY", "link": ["tmlab::mesh", "tmlab::hdf5", "tmlab::base"],
                 "interface": ["tmlab::mesh", "$<LINK_ONLY:tmlab::hdf5>", "$<LINK_ONLY:tmlab::base>"]},
    "tmlab_checks": {"type": "STATIC_LIBRARY", "link": ["tmlab::mesh"], "interface": ["tmlab::mesh"]},
    "tmlab_hdf5": {"type": "INTERFACE_LIBRARY", "link": [], "interface": ["/usr/lib/libhdf5.so"]},
}


class CheckArchitectureTable(unittest.TestCase):
    def test_a_matching_table_passes(self):
        # reference_fem absent from the graph (no deal.II) and its optional use: both accepted
        self.assertEqual(cat.check(TABLE, GRAPH), [])

    def test_a_wrong_row_is_named_with_the_difference(self):
        errors = cat.check(TABLE.replace("| base, Eigen |", "| base |"), GRAPH)
        self.assertEqual(len(errors), 1)
        self.assertIn("row `tmlab::mesh`", errors[0])
        self.assertIn("CMake links Eigen, the table does not say so", errors[0])

    def test_an_item_the_target_does_not_link_is_named(self):
        errors = cat.check(TABLE.replace("| base, Eigen |", "| base, Eigen, io |"), GRAPH)
        self.assertEqual(len(errors), 1)
        self.assertIn("the table says io, CMake does not link it", errors[0])

    def test_public_and_private_are_told_apart(self):
        errors = cat.check(TABLE.replace("| mesh (privately HDF5", "| mesh, HDF5 (privately"), GRAPH)
        self.assertEqual(len(errors), 1)
        self.assertIn("row `tmlab::io`", errors[0])
        self.assertIn("public: the table says HDF5", errors[0])
        self.assertIn("private: CMake links HDF5", errors[0])

    def test_an_optional_item_must_still_be_linked_when_listed_plainly(self):
        errors = cat.check(TABLE.replace("reference_fem (when built)", "reference_fem"), GRAPH)
        self.assertEqual(len(errors), 1)
        self.assertIn("row `tmlab::checks`", errors[0])

    def test_a_target_without_a_row_and_a_row_without_a_target(self):
        graph = dict(GRAPH, tmlab_extra={"type": "STATIC_LIBRARY", "link": [], "interface": []})
        errors = cat.check(TABLE.replace("`tmlab::checks`", "`tmlab::chekcs`"), graph)
        self.assertTrue(any("tmlab_extra has no row" in e for e in errors), errors)
        self.assertTrue(any("row `tmlab::chekcs`: no such CMake target" in e for e in errors), errors)
        self.assertTrue(any("tmlab_checks has no row" in e for e in errors), errors)

    def test_rows_after_the_module_table_are_not_read(self):
        self.assertNotIn("tmlab_nothing", cat.table_rows(TABLE))


if __name__ == "__main__":
    unittest.main()
