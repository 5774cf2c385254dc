// Keeps mrsv_metrics a valid library while its source list is empty.
namespace mrsv::metrics_anchor {
int unused = 0;
}
