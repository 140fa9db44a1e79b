"""pytest set-up for tools/nsm: the modules import each other by name, and every test that
needs a data set gets the tiny synthetic one (nsm_synthetic.py), written once per run."""
import os
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import nsm_synthetic  # noqa: E402


@pytest.fixture(scope="session")
def dataset_dir(tmp_path_factory):
    return nsm_synthetic.write_dataset(str(tmp_path_factory.mktemp("nsm_data")))
