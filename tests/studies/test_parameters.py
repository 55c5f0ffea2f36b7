"""block_from_dict checks each field of a block once, naming it by its key or by the caller's option."""
import pytest

from rockstudy.core import validation
from rockstudy.studies.parameters import BLOCK_FIELDS, block_from_dict


@pytest.fixture
def checked(quantity_checks):
    """The names of every Quantity.check call."""
    return quantity_checks


@pytest.mark.parametrize("spec", [{"width": 0.4, "height": 1.6, "depth": 0.4},
                                  {"width": 1.0, "height": 0.5, "depth": 0.4, "density": 2400.0, "gravity": 9.8,
                                   "restitution": 0.7}])
@pytest.mark.parametrize("names", [None, {"width": "--width", "height": "--height", "depth": "--depth"}])
def test_each_field_is_checked_once(spec, names, checked):
    block = block_from_dict(spec, names)
    assert all(getattr(block, key) == value for key, value in spec.items())
    assert len(checked) == len(BLOCK_FIELDS), checked  # every field of the block once, the defaults too
    for field in BLOCK_FIELDS:
        assert checked.count((names or {}).get(field, f"block.{field}")) == 1, (field, checked)


def test_a_missing_dimension_after_the_given_ones_each_checked_once(checked):
    with pytest.raises(validation.InputError, match=r"^block: missing key\(s\) \['depth'\]"):
        block_from_dict({"width": 0.4, "height": 1.6})
    assert checked == ["block.width", "block.height"]
    with pytest.raises(validation.InputError, match=r"^--width = -1 m is not allowed"):
        block_from_dict({"width": -1, "height": 1.6}, {"width": "--width"})


@pytest.mark.parametrize("names,restitution", [(None, "block.restitution"),
                                               ({"restitution": "--restitution"}, "--restitution")])
def test_a_squat_block_names_the_restitution_of_the_caller(names, restitution, checked):
    with pytest.raises(validation.InputError) as exc:
        block_from_dict({"width": 1.0, "height": 0.5, "depth": 0.4}, names)
    message = str(exc.value)
    assert message.startswith("block: width 1 m and height 0.5 m give alpha = 63.4 deg")
    assert message.endswith(f"or an explicit {restitution} in [0, 1]") and "Block" not in message
    assert len(checked) == len(BLOCK_FIELDS)
