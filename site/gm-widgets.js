/* The course website's widget set-up (tools/build_site.py copies it into _static/). It runs after
   require.js and before the widget manager (@jupyter-widgets/html-manager's embed-amd.js): the
   widget modules the manager does not bring itself are served by the site, so nothing is ever
   fetched from a CDN. jupyter-matplotlib is ipympl's front end, taken from the ipympl wheel. */
(function () {
  var me = document.currentScript;
  var base = me ? me.src.replace(/[^\/]*$/, '') : '_static/';
  // The widget manager's bundles find their fonts beside the module they are defined as
  // (@jupyter-widgets/html-manager/dist/...): that is the site's widgets/ folder.
  window.require.config({paths: {'jupyter-matplotlib': base + 'ipympl/index',
                                 '@jupyter-widgets/html-manager/dist': base + 'widgets'}});
})();
