"""What the `swarm` package's tests share."""

import pytest


@pytest.fixture(scope="session")
def ray_pool():
    """A local Ray cluster of 2 worker processes, for every test that asks for it."""
    import ray

    if ray.is_initialized():
        ray.shutdown()
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    yield ray
    ray.shutdown()
