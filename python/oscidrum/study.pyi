"""Type stubs of oscidrum.study."""

import concurrent.futures
import os
from typing import Any, Callable, Iterable, List, Optional, Sequence, Union

DEFAULT_CHUNK_SIZE: int

class Interrupted(KeyboardInterrupt):
    result: StudyResult
    def __init__(self, result: StudyResult) -> None: ...

class StudyResult(List[Any]):
    cases: List[Any]
    def __init__(self, cases: Sequence[Any], outcomes: Iterable[Any]) -> None: ...
    def to_dataframe(self, parameters: str = ...) -> Any: ...
    def to_xarray(self, dims: Optional[Sequence[str]] = ...) -> Any: ...
    def to_netcdf(self, path: Union[str, os.PathLike], dims: Optional[Sequence[str]] = ...
                  ) -> Union[str, os.PathLike]: ...

def run_chunk(cases: Sequence[Any], threads: int = ..., keep_samples: bool = ...,
              n_harmonics: int = ...) -> List[Any]: ...

def run_study(cases: Iterable[Any], threads: int = ..., keep_samples: bool = ...,
              n_harmonics: int = ...,
              progress: Union[None, bool, Callable[[int, int], Any]] = ...,
              on_case_done: Optional[Callable[[int, Any], Any]] = ...,
              executor: Optional[concurrent.futures.Executor] = ...,
              chunk_size: Optional[int] = ...,
              samples_in_callback: bool = ...) -> StudyResult: ...
