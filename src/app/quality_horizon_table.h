/* Placeholder until tools/tradeoff --emit-horizon-table has run. */
typedef struct quality_horizon { const char *config; int scene; double max, mean; } quality_horizon;
static const quality_horizon quality_horizon_table[] = {
    {"", -1, 0.0, 0.0},
};
static const int quality_horizon_table_count =
    (int)(sizeof quality_horizon_table / sizeof quality_horizon_table[0]);
