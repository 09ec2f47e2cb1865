"""Jobs: the settings registry under Python names, with the command line's checks and messages."""
import copy

import pytest

import fresnel


def test_names_keys_and_flags():
    job = fresnel.Job(yaw=30, camera_pitch=10, size=(320, 200), env="studio", shadow_map_size=1024)
    assert job.get("camera.yaw") == 30.0
    assert job["pitch"] == 10.0
    assert job["--pitch"] == 10.0
    assert job["render_size"] == (320, 200)
    assert job["environment"] == "studio"
    assert job["render.shadowMapSize"] == 1024
    job.set("camera.yaw", -15).update(exposure=1.5)
    assert job["yaw"] == -15.0 and job["exposure"] == 1.5
    assert fresnel.Job({"camera.fov": 30})["fov"] == 30.0


def test_values_by_type():
    job = fresnel.Job(background=(0.1, 0.2, 0.3), target=(1, 2, 3), shadows="hard", render_energy_compensation=False)
    assert job["target"] == (1.0, 2.0, 3.0)
    assert job["shadows"] == "hard"
    assert job["render_energy_compensation"] is False
    assert job["distance"] is None  # unset: fit
    job["distance"] = 2.5
    assert job["distance"] == 2.5
    job["distance"] = None
    assert job["distance"] is None
    assert fresnel.Job(size="64x48")["size"] == (64, 48)


def test_defaults_repr_copy_and_equality():
    job = fresnel.Job()
    assert job.settings() == {}
    everything = job.settings(all=True)
    assert everything["render_size"] == (1024, 768)
    assert everything["camera_fov"] == 45.0
    a = fresnel.Job(yaw=10)
    assert "camera_yaw=10.0" in repr(a)
    b = a.copy(pitch=5)
    assert a["pitch"] == 0.0 and b["pitch"] == 5.0 and b["yaw"] == 10.0
    assert copy.copy(a) == a and copy.deepcopy(a) == a and a != b
    assert a.settings() == {"camera_yaw": 10.0}


def test_unknown_names_are_type_errors_with_a_suggestion():
    with pytest.raises(TypeError, match="unknown setting 'szie'.*did you mean 'size'"):
        fresnel.Job(szie=(64, 64))
    with pytest.raises(TypeError):
        fresnel.Job().get("no_such_setting")


def test_bad_values_raise_fresnel_error_naming_the_setting():
    with pytest.raises(fresnel.Error) as e:
        fresnel.Job(pitch=95)
    assert e.value.file == "pitch"
    assert "[-90, 90]" in str(e.value) and "95" in str(e.value)
    assert isinstance(e.value, ValueError)
    with pytest.raises(fresnel.Error, match="expected"):
        fresnel.Job(shadows="fuzzy")
    with pytest.raises(fresnel.Error):
        fresnel.Job(size=(0, 10))


def test_wrong_python_types_are_type_errors():
    with pytest.raises(TypeError, match="yaw"):
        fresnel.Job(yaw=True)
    with pytest.raises(TypeError):
        fresnel.Job(yaw=None)  # yaw has no "unset"
    with pytest.raises(TypeError):
        fresnel.Job(target=(1, "a", 3))


def test_lights():
    job = fresnel.Job().add_light("dir:30,45,3").add_light("point:0,1,0,10")
    assert job.light_count == 2
    assert "lights=2" in repr(job)
    job.clear_lights()
    assert job.light_count == 0
    with pytest.raises(fresnel.Error):
        fresnel.Job().add_light("sun:1,2")


def test_registry_listing():
    entries = fresnel.settings()
    keys = {e["key"] for e in entries}
    assert {"camera.yaw", "render.size", "environment", "render.shadows"} <= keys
    names = [e["python"] for e in entries] + [a for e in entries for a in e["aliases"]]
    assert len(names) == len(set(names)), "each Python name means one setting"
    yaw = next(e for e in entries if e["key"] == "camera.yaw")
    assert yaw["python"] == "camera_yaw" and "yaw" in yaw["aliases"] and yaw["doc"]
    # Every listed name is accepted by Job with the setting's example value.
    for e in entries:
        job = fresnel.Job()
        job.set(e["python"], e["example"])
